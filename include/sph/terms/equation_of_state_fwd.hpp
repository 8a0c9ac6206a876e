// The equation-of-state choice, declared (terms/equation_of_state.hpp
// defines it, a std::variant of the EOS types): what a header that only
// holds or passes an EquationOfState by pointer or reference includes, so
// that touching an EOS rebuilds the units that evaluate one, not every unit
// that sees a model or the method tables.
#pragma once

namespace sph {

struct EquationOfState;

}  // namespace sph
