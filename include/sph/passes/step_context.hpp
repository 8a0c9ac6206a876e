// What every pass of a model is told about the step it works in.
#pragma once

#include "sph/types.hpp"

namespace sph {

struct StepContext {
  long step = 0;   // index of the step being computed (0: the initial state)
  Real time = 0;   // simulated time of the state being evaluated [s]
  Real dt = 0;     // the step's dt [s] (0 before the first step)
};

}  // namespace sph
