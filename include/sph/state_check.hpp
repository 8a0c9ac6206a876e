// StateCheck<D>: after every step, every value must be finite and every
// particle inside the domain. The first offending particle (the lowest
// sorted index) is reported with the quantity that failed, so a run that
// blows up stops with an explanation instead of writing garbage. The scene
// calls ok() per particle inside the step's last loop (no pass of its own).
#pragma once

#include "sph/particles.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace sph {

struct StateFailure {
  std::size_t index;      // sorted position
  std::int64_t id;        // particle id
  std::string quantity;   // "position", "velocity", "acceleration", "density", "domain", "wall"
  std::string detail;
};

template <int D>
struct StateCheck {
  StateCheck(const Vec<D>& lo_, const Vec<D>& hi_) : lo(lo_), hi(hi_) {}

  Vec<D> lo, hi;
  bool wallParticles = false;  // the box's walls are particles: a fluid particle outside it went through one
  bool openTop = false;        // ... except the top, which has none (no lid)
  // How far a fluid particle may pass a face of the box (or enter an
  // obstacle) before it counts as leaked: with wall particles dx/2, the
  // distance to the first layer of wall particles, since a particle near
  // a wall may stray a little past the wall line and be pushed back.
  Real tolerance = 0;
  using Box = AxisBox<D>;
  std::vector<Box> obstacles;  // solid boxes a fluid particle must not enter

  // (Inlined into the step's last loop, Scene::finishStep, with
  // inObstacle(): GCC left them out of line once that unit had less code to
  // inline into, and a dam-break step took 0.5% more instructions.)
  [[gnu::always_inline]] bool ok(const Particles<D>& P, std::size_t i) const {
    const Vec<D>& x = P.x[i];
    const bool finite = x.allFinite() && P.v[i].allFinite() && P.a[i].allFinite() && std::isfinite(P.rho[i]);
    if (i >= P.fluidCount()) return finite;  // wall particles live outside the box
    return finite && inside(x, lo.array() - tolerance, hi.array() + tolerance) && !inObstacle(x);
  }

  StateFailure describe(const Particles<D>& P, std::size_t i) const {
    StateFailure f{i, P.id[i], "", ""};
    if (!P.x[i].allFinite()) {
      f.quantity = "position";
      f.detail = "position " + vecString(P.x[i]) + " is not finite";
    } else if (!P.a[i].allFinite()) {
      f.quantity = "acceleration";
      f.detail = "acceleration " + vecString(P.a[i]) +
                 " is not finite (two particles at the same position make the "
                 "pressure kernel r_ij/q singular)";
    } else if (!P.v[i].allFinite()) {
      f.quantity = "velocity";
      f.detail = "velocity " + vecString(P.v[i]) + " is not finite";
    } else if (!std::isfinite(P.rho[i])) {
      f.quantity = "density";
      f.detail = "density " + std::to_string(P.rho[i]) + " is not finite";
    } else if (i < P.fluidCount() && inObstacle(P.x[i])) {
      f.quantity = "wall";
      f.detail = "fluid particle at " + vecString(P.x[i]) + " is inside an obstacle: it leaked through its wall "
                 "particles (too few wall layers, or too large a dt)";
    } else if (openTop && P.x[i][D - 1] > hi[D - 1]) {
      f.quantity = "domain";
      f.detail = "fluid particle at " + vecString(P.x[i]) + " left the domain through its open top (at " +
                 std::to_string(hi[D - 1]) + ", no lid): raise domain_max or close the tank with lid = true";
    } else if (wallParticles) {
      f.quantity = "wall";
      f.detail = "fluid particle at " + vecString(P.x[i]) + " is outside the domain " + vecString(lo) + " - " +
                 vecString(hi) + ": it leaked through the wall particles (too few wall layers, or too large a dt)";
    } else {
      f.quantity = "domain";
      f.detail = "position " + vecString(P.x[i]) + " is outside the domain " +
                 vecString(lo) + " - " + vecString(hi);
    }
    return f;
  }

 private:
  template <class A, class B>
  static bool inside(const Vec<D>& x, const A& a, const B& b) {
    return (x.array() >= a).all() && (x.array() <= b).all();
  }
  [[gnu::always_inline]] bool inObstacle(const Vec<D>& x) const {
    for (const Box& b : obstacles)
      if ((x.array() > b.lo.array() + tolerance).all() && (x.array() < b.hi.array() - tolerance).all()) return true;
    return false;
  }

  static std::string vecString(const Vec<D>& v) {
    std::string s = "(";
    for (int d = 0; d < D; ++d) s += (d ? ", " : "") + std::to_string(v[d]);
    return s + ")";
  }

};

}  // namespace sph
