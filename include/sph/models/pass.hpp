// Pass<D>: a model's pass as the model, the scene and the tests see it: an
// object with run(P, neighbours, ctx) (the term bits it ran), the fields it
// reads and writes at a step (fields(ctx), fields.hpp), its name and what
// the model asks of it besides evaluating (role()). One virtual call per
// pass and evaluation, never per pair: the pair loops stay inside each
// pass's run(), compiled once in src/.
//
// The passes themselves are value types (passes/*.hpp), wrapped when a
// model is built (makePass, in the files that build models: src/*_model.cpp
// and the boundaries' hooks). Everything that only runs a model (model.hpp,
// scene.hpp, the factory's callers) includes this interface alone, so a
// change to a term or to the pair loop rebuilds only the files that build
// or compile the passes (issue 18; bench/rebuild_fraction.py).
#pragma once

#include "sph/fields.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace sph {

template <int D>
class NeighbourList;  // neighbour_list.hpp
template <int D>
struct SummationDensityPass;  // passes/summation_density.hpp
template <int D>
struct CspmCorrectionPass;  // passes/cspm_correction.hpp

// What the model runs a pass for outside an evaluation: the density alone
// (the mass scaling, Model::computeDensity) or the CSPM matrices alone (a
// resume, a density re-initialisation: Model::refreshCspmMatrices).
enum class PassRole { kOther, kSummationDensity, kCspmMatrices };

template <int D>
class Pass {
 public:
  virtual ~Pass() = default;
  virtual unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const = 0;
  virtual FieldAccess fields(const StepContext& ctx) const = 0;
  virtual const char* name() const = 0;
  virtual PassRole role() const = 0;
};

// An ordered list of passes. The passes do not change once built, so a
// copied model shares them.
template <int D>
using PassList = std::vector<std::shared_ptr<const Pass<D>>>;

// A pass value type T (run(), fields(), static name) as a Pass<D>.
template <int D, class T>
class PassOf final : public Pass<D> {
 public:
  explicit PassOf(T pass) : pass_(std::move(pass)) {}
  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const override {
    return pass_.run(P, neighbours, ctx);
  }
  FieldAccess fields(const StepContext& ctx) const override { return pass_.fields(ctx); }
  const char* name() const override { return T::name; }
  PassRole role() const override {
    if constexpr (std::is_same_v<T, SummationDensityPass<D>>) return PassRole::kSummationDensity;
    else if constexpr (std::is_same_v<T, CspmCorrectionPass<D>>) return PassRole::kCspmMatrices;
    else return PassRole::kOther;
  }

 private:
  T pass_;
};

template <template <int> class T, int D>
std::shared_ptr<const Pass<D>> makePass(T<D> pass) {
  return std::make_shared<const PassOf<D, T<D>>>(std::move(pass));
}

}  // namespace sph
