// One bit per physics pass. The model ORs together the bits of the passes it
// actually ran in its last evaluation (the bits come from the term types
// instantiated in the pair loop, not from the case's flags), so a test can
// show that a switched-off term never runs.
#pragma once

namespace sph::term_bits {

enum : unsigned {
  kSummationDensity = 1u << 0,
  kEquationOfState = 1u << 1,
  kSeedPressure = 1u << 2,
  kSeedViscosity = 1u << 3,
  kSymmetricPressure = 1u << 4,
  kLaplacianViscosity = 1u << 5,
  kMonaghanViscosity = 1u << 6,
  kGravity = 1u << 7,
  kStarAttraction = 1u << 8,
  kDamping = 1u << 9,
  kXsph = 1u << 10,
  kContinuityDensity = 1u << 11,
  kDensityDiffusion = 1u << 12,
  kAdamiWalls = 1u << 13,
  kDynamicWalls = 1u << 14,
  kRepulsiveWalls = 1u << 15,
  kMorrisViscosity = 1u << 16,
  kShepardDensity = 1u << 17,  // density re-initialisation, zeroth order
  kMlsDensity = 1u << 18,      // density re-initialisation, first order (MLS)
  kCspmCorrection = 1u << 19,  // the L_i pre-pass
  kCspmPressure = 1u << 20,    // the pressure gradient with L_i
  kArtificialPressure = 1u << 21,
  kColourField = 1u << 22,
  kSurfaceTension = 1u << 23,
  // An optional term that names no bit of its own: this << its index in
  // the list of terms/optional_terms.hpp (room for 8).
  kFirstListedTerm = 1u << 24,
};

}  // namespace sph::term_bits
