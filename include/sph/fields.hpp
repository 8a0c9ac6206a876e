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
//   list     the neighbour list's own record (with a Verlet skin, scene.hpp:
//            the positions of its last build), rewritten at every rebuild,
//            so never permuted or carried, and not copied to ghosts;
//            written to snapshots so that a resume rebuilds the same list
// Rates and derived fields are stale after a permute until the model
// evaluates again, so they are not permuted. Density is state when it is
// integrated (continuity density, with a drho field) and derived when it
// is summed; Particles::allocate() permutes it only in the first case.
#pragma once

#include <cstdint>

namespace sph {

enum class FieldRole : std::uint8_t { kState, kStage, kRate, kDerived, kList };

enum FieldId : unsigned {
  kFieldX,         // position [m]
  kFieldV,         // velocity at integer time [m/s]
  kFieldA,         // acceleration [m/s^2]
  kFieldRho,       // density [kg/m^D]
  kFieldDrho,      // density rate d rho/dt (continuity density) [kg/(m^D s)]
  kFieldP,         // pressure [Pa, N/m in 2D]
  kFieldM,         // mass [kg, also in 2D: rho0 [kg/m^2] times dx^2]
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
  kFieldVPrev,     // two-step leap-frog: the filtered velocity of the step before
  kFieldRhoPrev,   // ... and density
  kFieldXList,     // position at the neighbour list's last build (skin > 0, or the cell walk) [m]
  kFieldShiftSum,  // particle shifting: the kernel sum sum_j V_j W_ij at the last evaluation
  kFieldShiftGrad, // ... and the concentration gradient grad C_i (particle_shifting.hpp) [1/m]
  kFieldCount
};

using FieldSet = std::uint32_t;

constexpr FieldSet fieldBit(FieldId f) { return FieldSet(1) << f; }

// The set of the fields given.
template <class... F>
constexpr FieldSet fieldBits(F... f) {
  return (FieldSet(0) | ... | fieldBit(f));
}

// What a pass of a model reads and writes (each pass's fields(), next to its
// run(); Model::sync()): `reads`, the fields whose values, at a particle or
// at its neighbours (ghosts included), its results depend on; `writes`, the
// fields it may change (of the owned particles: a pass never writes a
// ghost's own value, except by copying it from its source). A field a pass
// writes without reading first is not in `reads`; one it adds to (a += ...)
// is in both. The ghosts and halos of `writes` are refreshed after the
// pass (but for the fields read only at their own particle,
// kOwnParticleFields below). tests/test_pass_fields.cpp checks both sets.
struct FieldAccess {
  FieldSet reads = 0;
  FieldSet writes = 0;
};

// The fields every scene has.
constexpr FieldSet kCoreFields = fieldBit(kFieldX) | fieldBit(kFieldV) | fieldBit(kFieldA) |
                                 fieldBit(kFieldRho) | fieldBit(kFieldP) | fieldBit(kFieldM) |
                                 fieldBit(kFieldId);

struct FieldInfo {
  FieldId id;
  const char* name;      // name in code and messages
  FieldRole role;
  const char* vtkName;   // point-data array in a snapshot; nullptr: not written
  const char* unit3;     // SI unit in 3D ("1": dimensionless, a count or a label)
  const char* unit2;     // ... in 2D, per unit depth: density kg/m^2, pressure N/m
  const char* unit(int dimension) const { return dimension == 2 ? unit2 : unit3; }
};

inline constexpr FieldInfo kFieldTable[kFieldCount] = {
    {kFieldX, "x", FieldRole::kState, nullptr, "m", "m"},  // the points themselves
    {kFieldV, "v", FieldRole::kState, "velocity", "m/s", "m/s"},
    {kFieldA, "a", FieldRole::kRate, "acceleration", "m/s^2", "m/s^2"},
    {kFieldRho, "rho", FieldRole::kState, "density", "kg/m^3", "kg/m^2"},
    {kFieldDrho, "drho", FieldRole::kRate, "density_rate", "kg/m^3/s", "kg/m^2/s"},
    {kFieldP, "p", FieldRole::kDerived, "pressure", "Pa", "N/m"},
    {kFieldM, "m", FieldRole::kState, "mass", "kg", "kg"},
    {kFieldId, "id", FieldRole::kState, "id", "1", "1"},
    {kFieldKind, "kind", FieldRole::kState, "kind", "1", "1"},
    {kFieldVHalf, "vHalf", FieldRole::kStage, nullptr, "m/s", "m/s"},
    {kFieldC, "c", FieldRole::kDerived, nullptr, "m/s", "m/s"},
    {kFieldVXsph, "vXsph", FieldRole::kDerived, "xsph_velocity", "m/s", "m/s"},
    {kFieldVWall, "vWall", FieldRole::kDerived, nullptr, "m/s", "m/s"},
    {kFieldX0, "x0", FieldRole::kStage, nullptr, "m", "m"},
    {kFieldV0, "v0", FieldRole::kStage, nullptr, "m/s", "m/s"},
    {kFieldRho0, "rho0", FieldRole::kStage, nullptr, "kg/m^3", "kg/m^2"},
    {kFieldDx, "dx", FieldRole::kStage, nullptr, "m/s", "m/s"},
    {kFieldDv, "dv", FieldRole::kStage, nullptr, "m/s^2", "m/s^2"},
    {kFieldDrhoSum, "drhoSum", FieldRole::kStage, nullptr, "kg/m^3/s", "kg/m^2/s"},
    {kFieldRhoReinit, "rhoReinit", FieldRole::kDerived, nullptr, "kg/m^3", "kg/m^2"},
    {kFieldCspmL, "cspmL", FieldRole::kDerived, nullptr, "1", "1"},
    {kFieldColour, "colour", FieldRole::kState, "colour", "1", "1"},
    {kFieldColourNormal, "colourNormal", FieldRole::kDerived, "colour_normal", "1/m", "1/m"},
    {kFieldCurvature, "curvature", FieldRole::kDerived, "curvature", "1/m", "1/m"},
    {kFieldVPrev, "vPrev", FieldRole::kState, "velocity_previous", "m/s", "m/s"},
    {kFieldRhoPrev, "rhoPrev", FieldRole::kState, "density_previous", "kg/m^3", "kg/m^2"},
    {kFieldXList, "xList", FieldRole::kList, "list_build_position", "m", "m"},
    {kFieldShiftSum, "shiftSum", FieldRole::kDerived, nullptr, "1", "1"},
    {kFieldShiftGrad, "shiftGrad", FieldRole::kDerived, nullptr, "1/m", "1/m"},
};

constexpr bool isPermuted(FieldRole r) { return r == FieldRole::kState || r == FieldRole::kStage; }

// The fields of the list role (see the top): neither carried nor refreshed.
constexpr FieldSet kListFields = fieldBit(kFieldXList);

// Fields read only at their own particle, never at a neighbour: particle
// shifting's sums, which the shift of the particle itself reads. Their
// ghosts and halos are never refreshed (Particles::refreshGhosts).
constexpr FieldSet kOwnParticleFields = fieldBits(kFieldShiftSum, kFieldShiftGrad);

// Particle kinds (the kind field). Walls are stored after all fluid particles.
enum ParticleKind : std::uint8_t { kFluid = 0, kWall = 1 };

}  // namespace sph
