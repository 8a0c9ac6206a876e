// The kernel family: one value type per kernel, each `template <int D>` with
// W, dWdr, gradW, laplacianW and support (see each header for its equations
// and source). The seed scheme's own kernels stay in seed_kernels.hpp.
#pragma once

#include "sph/kernels/cubic_spline.hpp"
#include "sph/kernels/gaussian.hpp"
#include "sph/kernels/muller.hpp"
#include "sph/kernels/wendland_c2.hpp"

#include <variant>

namespace sph {

// The kernel of a wcsph model, chosen by name (methods.hpp).
template <int D>
using Kernel = std::variant<CubicSpline<D>, WendlandC2<D>, Gaussian<D>, Muller<D>>;

}  // namespace sph
