// Linear damping a_i = -nu v_i: drains kinetic energy so a scene relaxes to
// equilibrium (the toy star's relaxation). An optional term
// (optional_terms.hpp): key `damping` (nu, 0: off), added to each fluid
// particle's acceleration in the force pass's epilogue after the body
// forces; off, it is one predictable branch per particle.
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/case_keys.hpp"
#include "sph/fields.hpp"
#include "sph/particles.hpp"

#include <vector>

namespace sph {

struct LinearDamping {
  static constexpr const char* name = "damping";
  static constexpr unsigned bit = term_bits::kDamping;
  static constexpr bool kPerPair = false;  // per particle: acceleration()
  Real nu = 0;                             // 0: off

  static std::vector<KeySpec> keys() {
    return {termKey("damping", KeyGroup::kPhysics, "1/s", "Linear damping nu in a = -nu v (model wcsph; 0: off)",
                    key_range::within(0, 1e6), Real(0))};
  }
  static LinearDamping fromCase(const CaseConfig& c) { return {termReal(c, "damping")}; }
  static void validate(const CaseConfig&) {}
  template <class Note>
  static void noteUnused(const CaseConfig&, Note&&) {}

  bool active() const { return nu > 0; }
  FieldSet reads() const { return fieldBit(kFieldV); }

  template <int D>
  Vec<D> acceleration(std::size_t i, const Particles<D>& P) const { return -nu * P.v[i]; }
};

}  // namespace sph
