// The table of particle fields: one row per per-particle array, with its
// name, its role and the name it has in a .vtp snapshot. Allocation,
// permutation, memory accounting, the snapshot writer and the resume reader
// all loop over this table (Particles::forEachField), so a new field is one
// row here and one member in Particles.
//
// Roles:
//   state    defines the particles between steps: permuted by a re-sort,
//            written to every snapshot and read back by a resume
//   stage    an integrator's values inside one step (a step re-sorts between
//            its stages, so they are permuted too), never written
//   rate     d/dt of a state field, recomputed by every evaluation
//   derived  recomputed from the state by every evaluation (pressure, ...)
// Rates and derived fields are stale after a permute until the model
// evaluates again, so they are not permuted. Density is state when it is
// integrated (continuity density, with a drho field) and derived when it
// is summed; Particles::allocate() permutes it only in the first case.
#pragma once

#include <cstdint>

namespace sph {

enum class FieldRole : std::uint8_t { kState, kStage, kRate, kDerived };

enum FieldId : unsigned {
  kFieldX,         // position [m]
  kFieldV,         // velocity at integer time [m/s]
  kFieldA,         // acceleration [m/s^2]
  kFieldRho,       // density [kg/m^D]
  kFieldDrho,      // density rate d rho/dt (continuity density)
  kFieldP,         // pressure [Pa, N/m in 2D]
  kFieldM,         // mass [kg, kg/m in 2D]
  kFieldId,        // stable identity
  kFieldKind,      // 0 fluid, 1 wall (walls are contiguous, after the fluid)
  kFieldVHalf,     // leap-frog half-step velocity
  kFieldC,         // sound speed
  kFieldVXsph,     // XSPH velocity correction, added to the drift
  kFieldVWall,     // velocity a wall particle shows the fluid (no-slip extrapolation)
  kFieldX0,        // RK4: state at the start of the step
  kFieldV0,
  kFieldRho0,
  kFieldDx,        // RK4: weighted sums of the stage derivatives
  kFieldDv,
  kFieldDrhoSum,
  kFieldRhoReinit, // density re-initialisation (Shepard, MLS): the new densities, before they replace rho
  kFieldCspmL,     // CSPM gradient correction L_i (D x D)
  kFieldColour,    // colour (phase) of a fluid particle: 1 in the phase with surface tension, 0 outside
  kFieldColourNormal,     // colour-field normal n = grad c (surface tension)
  kFieldCurvature,        // curvature kappa of the colour field's surface (surface tension)
  kFieldCount
};

using FieldSet = std::uint32_t;

constexpr FieldSet fieldBit(FieldId f) { return FieldSet(1) << f; }

// The fields every scene has.
constexpr FieldSet kCoreFields = fieldBit(kFieldX) | fieldBit(kFieldV) | fieldBit(kFieldA) |
                                 fieldBit(kFieldRho) | fieldBit(kFieldP) | fieldBit(kFieldM) |
                                 fieldBit(kFieldId);

struct FieldInfo {
  FieldId id;
  const char* name;      // name in code and messages
  FieldRole role;
  const char* vtkName;   // point-data array in a snapshot; nullptr: not written
};

inline constexpr FieldInfo kFieldTable[kFieldCount] = {
    {kFieldX, "x", FieldRole::kState, nullptr},  // the points themselves
    {kFieldV, "v", FieldRole::kState, "velocity"},
    {kFieldA, "a", FieldRole::kRate, "acceleration"},
    {kFieldRho, "rho", FieldRole::kState, "density"},
    {kFieldDrho, "drho", FieldRole::kRate, "density_rate"},
    {kFieldP, "p", FieldRole::kDerived, "pressure"},
    {kFieldM, "m", FieldRole::kState, "mass"},
    {kFieldId, "id", FieldRole::kState, "id"},
    {kFieldKind, "kind", FieldRole::kState, "kind"},
    {kFieldVHalf, "vHalf", FieldRole::kStage, nullptr},
    {kFieldC, "c", FieldRole::kDerived, nullptr},
    {kFieldVXsph, "vXsph", FieldRole::kDerived, "xsph_velocity"},
    {kFieldVWall, "vWall", FieldRole::kDerived, nullptr},
    {kFieldX0, "x0", FieldRole::kStage, nullptr},
    {kFieldV0, "v0", FieldRole::kStage, nullptr},
    {kFieldRho0, "rho0", FieldRole::kStage, nullptr},
    {kFieldDx, "dx", FieldRole::kStage, nullptr},
    {kFieldDv, "dv", FieldRole::kStage, nullptr},
    {kFieldDrhoSum, "drhoSum", FieldRole::kStage, nullptr},
    {kFieldRhoReinit, "rhoReinit", FieldRole::kDerived, nullptr},
    {kFieldCspmL, "cspmL", FieldRole::kDerived, nullptr},
    {kFieldColour, "colour", FieldRole::kState, "colour"},
    {kFieldColourNormal, "colourNormal", FieldRole::kDerived, "colour_normal"},
    {kFieldCurvature, "curvature", FieldRole::kDerived, "curvature"},
};

constexpr bool isPermuted(FieldRole r) { return r == FieldRole::kState || r == FieldRole::kStage; }

// Particle kinds (the kind field). Walls are stored after all fluid particles.
enum ParticleKind : std::uint8_t { kFluid = 0, kWall = 1 };

}  // namespace sph
