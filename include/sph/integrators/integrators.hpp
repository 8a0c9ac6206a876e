// The time integrators, as one variant: adding a type here registers it
// (methods.hpp lists the alternatives by their own name and summary).
#pragma once

#include "sph/integrators/explicit_euler.hpp"
#include "sph/integrators/leap_frog.hpp"
#include "sph/integrators/runge_kutta4.hpp"
#include "sph/integrators/symplectic_euler.hpp"
#include "sph/integrators/two_step_leap_frog.hpp"

#include <variant>

namespace sph {

template <int D>
using Integrator = std::variant<LeapFrog<D>, SymplecticEuler<D>, RungeKutta4<D>, ExplicitEuler<D>, TwoStepLeapFrog<D>>;

}  // namespace sph
