// sph-pair-layouts: what one neighbour walk costs per pair in the data
// layouts a vectorised pair loop could use (issue 19), on the walk sph
// runs for every leap-frog step: the density rate of continuity density
// with Fourtakas' delta-SPH diffusion,
//
//   D_i = sum_j m_j (v_i - v_j) . grad_i W_ij
//       + 2 delta h c0 sum_j V_j psi_ij (-r_ij . grad_i W_ij) / (r_ij^2 + 0.01 h^2),
//   psi_ij = (rho_j - rho_i) - rho0 (g . r_ij) / c0^2,  grad_i W_ij = F(r) r_ij,
//
// with Wendland C2 (F(r) = -5 sigma / h^4 (1 - q/2)^3 in 2D, no division),
// on a jittered 2D lattice sorted by cell, h = 1.5 dx, a list radius of
// 2h (1 + 0.1) (sph's default skin). Each layout computes the same sums;
// the program prints CPU ns per pair inside the support (the best of 5
// walks, one thread), the work it did per such pair, and the largest
// difference from the scalar walk (round-off for double; float's own
// error for float, whose density differences lose digits: rho ~ 1000 kg/m^2
// in float has 6e-5 resolution, psi is a difference of such numbers).
//
//   scalar   sph's form: a stored list of neighbour indices per particle,
//            one pair at a time (the pair loop of include/sph/pair_loop.hpp)
//   gather8  the same list in blocks of 8 neighbours, the block's data
//            gathered into SIMD lanes (omp simd)
//   rows     no list: the candidates of a particle are the 3 contiguous
//            runs of sorted particles in its stencil's cell rows, walked
//            with plain vector loads and a mask (the kernel is 0 beyond
//            the support); cells of the list radius
//   cluster  GROMACS-like cluster pairs: clusters of C consecutive sorted
//            particles; for each i-cluster a list of the j-clusters whose
//            boxes come within the list radius; every i of the cluster
//            against the C lanes of each j-cluster (contiguous loads)
//
// Build: sph-pair-layouts (CMakeLists.txt: -O3 -march=native
// -fno-math-errno, so that the simd loops vectorise). Run:
//   build/sph-pair-layouts [particles per side, default 240 x 250]
// Figures, not assertions; docs/performance.md quotes them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace {

struct Lattice {
  std::size_t n = 0;
  double dx = 0.0014, h = 1.5 * 0.0014, support = 3 * 0.0014, radius = 3 * 0.0014 * 1.1;
  int cx = 0, cy = 0;
  std::vector<double> x, y, vx, vy, rho, m, vol;  // sorted by cell (row-major, x fastest)
  std::vector<int> cellStart;                      // cells of edge `radius`
  int cellX(double px) const { return static_cast<int>(px / radius); }
  int cellY(double py) const { return static_cast<int>(py / radius); }
};

Lattice makeLattice(int nx, int ny) {
  Lattice L;
  std::mt19937 g(1);
  std::uniform_real_distribution<double> jitter(-0.1 * L.dx, 0.1 * L.dx);
  std::vector<double> px, py;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      px.push_back(0.01 + i * L.dx + jitter(g));
      py.push_back(0.01 + j * L.dx + jitter(g));
    }
  L.n = px.size();
  L.cx = L.cellX(0.02 + nx * L.dx) + 1;
  L.cy = L.cellY(0.02 + ny * L.dx) + 1;
  auto cell = [&](std::size_t i) { return L.cellY(py[i]) * L.cx + L.cellX(px[i]); };
  std::vector<std::size_t> order(L.n);
  for (std::size_t i = 0; i < L.n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cell(a) < cell(b); });
  L.cellStart.assign(static_cast<std::size_t>(L.cx * L.cy + 1), 0);
  for (std::size_t k = 0; k < L.n; ++k) {
    const std::size_t i = order[k];
    L.x.push_back(px[i]);
    L.y.push_back(py[i]);
    L.vx.push_back(0.1 * std::sin(50 * px[i]));
    L.vy.push_back(0.1 * std::cos(40 * py[i]));
    L.rho.push_back(1000 + 3 * py[i]);
    L.m.push_back(1000 * L.dx * L.dx);
    L.vol.push_back(L.m.back() / L.rho.back());
    ++L.cellStart[static_cast<std::size_t>(cell(i)) + 1];
  }
  for (std::size_t c = 1; c < L.cellStart.size(); ++c) L.cellStart[c] += L.cellStart[c - 1];
  return L;
}

// The walk's constants, in T.
template <class T>
struct Walk {
  T sigmaLap, invH, support2, coefficient, eta2, hydrostatic;
  explicit Walk(const Lattice& L)
      : sigmaLap(T(7 / (4 * M_PI) / std::pow(L.h, 4))), invH(T(1 / L.h)), support2(T(L.support * L.support)),
        coefficient(T(2 * 0.1 * L.h * 44)), eta2(T(0.01 * L.h * L.h)), hydrostatic(T(-1000 * 9.81 / (44 * 44))) {}
  // One pair's contribution to D_i (r0, r1 = r_ij; lanes beyond the support give 0).
  [[gnu::always_inline]] T pair(T r0, T r1, T dvx, T dvy, T mj, T vj, T rhoj, T rhoi) const {
    const T r2 = r0 * r0 + r1 * r1, r = std::sqrt(r2);
    const T t = std::max(T(1) - T(0.5) * r * invH, T(0));
    const T F = r2 < support2 ? T(-5) * sigmaLap * t * t * t : T(0);
    const T g0 = F * r0, g1 = F * r1;
    const T psi = (rhoj - rhoi) + hydrostatic * r1;
    return mj * (dvx * g0 + dvy * g1) + coefficient * vj * psi * (-(r0 * g0 + r1 * g1)) / (r2 + eta2);
  }
};

// The stored list: per particle, the neighbours within the list radius, in cell order.
struct List {
  std::vector<std::uint32_t> j, begin;
};

List buildList(const Lattice& L) {
  List list;
  const double R2 = L.radius * L.radius;
  for (std::size_t i = 0; i < L.n; ++i) {
    list.begin.push_back(static_cast<std::uint32_t>(list.j.size()));
    const int a = L.cellX(L.x[i]), b = L.cellY(L.y[i]);
    for (int bb = std::max(b - 1, 0); bb <= std::min(b + 1, L.cy - 1); ++bb) {
      const int c0 = bb * L.cx + std::max(a - 1, 0), c1 = bb * L.cx + std::min(a + 1, L.cx - 1);
      for (int k = L.cellStart[c0]; k < L.cellStart[c1 + 1]; ++k) {
        const double d0 = L.x[i] - L.x[k], d1 = L.y[i] - L.y[k];
        if (k != static_cast<int>(i) && d0 * d0 + d1 * d1 < R2) list.j.push_back(static_cast<std::uint32_t>(k));
      }
    }
  }
  list.begin.push_back(static_cast<std::uint32_t>(list.j.size()));
  return list;
}

void scalar(const Lattice& L, const List& list, std::vector<double>& out) {
  const Walk<double> w(L);
  for (std::size_t i = 0; i < L.n; ++i) {
    double sum = 0;
    for (std::uint32_t k = list.begin[i]; k < list.begin[i + 1]; ++k) {
      const std::uint32_t j = list.j[k];
      const double r0 = L.x[i] - L.x[j], r1 = L.y[i] - L.y[j];
      if (!(r0 * r0 + r1 * r1 < w.support2)) continue;  // in the skin
      sum += w.pair(r0, r1, L.vx[i] - L.vx[j], L.vy[i] - L.vy[j], L.m[j], L.vol[j], L.rho[j], L.rho[i]);
    }
    out[i] = sum;
  }
}

void gather8(const Lattice& L, const List& list, std::vector<double>& out) {
  constexpr int W = 8;
  const Walk<double> w(L);
  for (std::size_t i = 0; i < L.n; ++i) {
    double lane[W] = {};
    const std::uint32_t b = list.begin[i], e = list.begin[i + 1];
    for (std::uint32_t k = b; k < e; k += W) {
      std::uint32_t jj[W];
      for (int l = 0; l < W; ++l) jj[l] = k + l < e ? list.j[k + l] : static_cast<std::uint32_t>(i);  // i: r = 0, adds 0
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        const std::uint32_t j = jj[l];
        lane[l] += w.pair(L.x[i] - L.x[j], L.y[i] - L.y[j], L.vx[i] - L.vx[j], L.vy[i] - L.vy[j], L.m[j], L.vol[j],
                          L.rho[j], L.rho[i]);
      }
    }
    double sum = 0;
    for (double s : lane) sum += s;
    out[i] = sum;
  }
}

void rows(const Lattice& L, std::vector<double>& out, std::size_t& candidates) {
  const Walk<double> w(L);
  candidates = 0;
  for (std::size_t i = 0; i < L.n; ++i) {
    const int a = L.cellX(L.x[i]), b = L.cellY(L.y[i]);
    double sum = 0;
    const double xi = L.x[i], yi = L.y[i], vxi = L.vx[i], vyi = L.vy[i], rhoi = L.rho[i];
    for (int bb = std::max(b - 1, 0); bb <= std::min(b + 1, L.cy - 1); ++bb) {
      const int j0 = L.cellStart[bb * L.cx + std::max(a - 1, 0)],
                j1 = L.cellStart[bb * L.cx + std::min(a + 1, L.cx - 1) + 1];
      candidates += static_cast<std::size_t>(j1 - j0);
#pragma omp simd reduction(+ : sum)
      for (int j = j0; j < j1; ++j)
        sum += w.pair(xi - L.x[j], yi - L.y[j], vxi - L.vx[j], vyi - L.vy[j], L.m[j], L.vol[j], L.rho[j], rhoi);
    }
    out[i] = sum;
  }
}

// Cluster pairs: C consecutive particles a cluster (padded far away), in T.
template <class T, int C>
struct Clusters {
  std::size_t count = 0;
  std::vector<T> x, y, vx, vy, rho, m, vol;
  std::vector<std::uint32_t> j, begin;  // j-clusters of each i-cluster
};

template <class T, int C>
Clusters<T, C> buildClusters(const Lattice& L) {
  Clusters<T, C> c;
  c.count = (L.n + C - 1) / C;
  const std::size_t padded = c.count * C;
  auto fill = [&](std::vector<T>& to, const std::vector<double>& from, double pad) {
    to.assign(padded, T(pad));
    for (std::size_t i = 0; i < L.n; ++i) to[i] = T(from[i]);
  };
  fill(c.x, L.x, 1e6), fill(c.y, L.y, 1e6), fill(c.vx, L.vx, 0), fill(c.vy, L.vy, 0), fill(c.rho, L.rho, 1000);
  fill(c.m, L.m, 0), fill(c.vol, L.vol, 0);
  std::vector<double> lo0(c.count, 1e300), hi0(c.count, -1e300), lo1(c.count, 1e300), hi1(c.count, -1e300);
  for (std::size_t i = 0; i < L.n; ++i) {
    const std::size_t k = i / C;
    lo0[k] = std::min(lo0[k], L.x[i]), hi0[k] = std::max(hi0[k], L.x[i]);
    lo1[k] = std::min(lo1[k], L.y[i]), hi1[k] = std::max(hi1[k], L.y[i]);
  }
  const double R = L.radius;
  std::vector<std::uint32_t> candidates;
  for (std::size_t I = 0; I < c.count; ++I) {
    c.begin.push_back(static_cast<std::uint32_t>(c.j.size()));
    candidates.clear();
    for (int bb = std::max(L.cellY(lo1[I] - R), 0); bb <= std::min(L.cellY(hi1[I] + R), L.cy - 1); ++bb) {
      const int c0 = bb * L.cx + std::max(L.cellX(lo0[I] - R), 0), c1 = bb * L.cx + std::min(L.cellX(hi0[I] + R), L.cx - 1);
      for (int k = L.cellStart[c0]; k < L.cellStart[c1 + 1]; ++k) candidates.push_back(static_cast<std::uint32_t>(k / C));
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (std::uint32_t J : candidates) {
      const double g0 = std::max({0.0, lo0[J] - hi0[I], lo0[I] - hi0[J]});
      const double g1 = std::max({0.0, lo1[J] - hi1[I], lo1[I] - hi1[J]});
      if (g0 * g0 + g1 * g1 < R * R) c.j.push_back(J);
    }
  }
  c.begin.push_back(static_cast<std::uint32_t>(c.j.size()));
  return c;
}

template <class T, int C>
void cluster(const Lattice& L, const Clusters<T, C>& c, std::vector<double>& out) {
  const Walk<T> w(L);
  for (std::size_t I = 0; I < c.count; ++I) {
    T lane[C][C] = {};
    for (std::uint32_t k = c.begin[I]; k < c.begin[I + 1]; ++k) {
      const std::size_t j0 = std::size_t(c.j[k]) * C;
      for (int a = 0; a < C; ++a) {
        const std::size_t i = I * C + a;
        const T xi = c.x[i], yi = c.y[i], vxi = c.vx[i], vyi = c.vy[i], rhoi = c.rho[i];
#pragma omp simd
        for (int l = 0; l < C; ++l) {  // (i with itself: r = 0, so grad W and its terms are 0)
          const std::size_t j = j0 + l;
          lane[a][l] += w.pair(xi - c.x[j], yi - c.y[j], vxi - c.vx[j], vyi - c.vy[j], c.m[j], c.vol[j], c.rho[j], rhoi);
        }
      }
    }
    for (int a = 0; a < C; ++a) {
      const std::size_t i = I * C + a;
      if (i >= L.n) continue;
      double sum = 0;
      for (int l = 0; l < C; ++l) sum += lane[a][l];
      out[i] = sum;
    }
  }
}

template <class F>
double best(F&& f) {
  f();
  double t = 1e300;
  for (int k = 0; k < 5; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t = std::min(t, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return t;
}

double largestDifference(const std::vector<double>& a, const std::vector<double>& ref) {
  double scale = 0, worst = 0;
  for (double r : ref) scale = std::max(scale, std::abs(r));
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - ref[i]));
  return worst / scale;
}

}  // namespace

int main(int argc, char** argv) {
  const int nx = argc > 1 ? std::atoi(argv[1]) : 240, ny = argc > 2 ? std::atoi(argv[2]) : 250;
  const Lattice L = makeLattice(nx, ny);
  const List list = buildList(L);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < L.n; ++i)
    for (std::uint32_t k = list.begin[i]; k < list.begin[i + 1]; ++k) {
      const double d0 = L.x[i] - L.x[list.j[k]], d1 = L.y[i] - L.y[list.j[k]];
      pairs += d0 * d0 + d1 * d1 < L.support * L.support;
    }
  std::printf("# %zu particles (2D, h = 1.5 dx), %.1f pairs per particle in the support, %.1f listed (skin 0.1)\n",
              L.n, double(pairs) / L.n, double(list.j.size()) / L.n);
  std::printf("# %-14s %8s %14s %12s\n", "layout", "ns/pair", "work per pair", "vs scalar");
  std::vector<double> ref(L.n), out(L.n);
  const double perPair = 1e9 / double(pairs);
  double t = best([&] { scalar(L, list, ref); });
  std::printf("  %-14s %8.2f %11.2f li %12s\n", "scalar", t * perPair, double(list.j.size()) / pairs, "-");
  t = best([&] { gather8(L, list, out); });
  std::printf("  %-14s %8.2f %11.2f li %12.1e\n", "gather8", t * perPair, double(list.j.size()) / pairs,
              largestDifference(out, ref));
  std::size_t candidates = 0;
  t = best([&] { rows(L, out, candidates); });
  std::printf("  %-14s %8.2f %11.2f ca %12.1e\n", "rows", t * perPair, double(candidates) / pairs,
              largestDifference(out, ref));
  auto clusterRow = [&](auto tag, const char* name) {
    using Cl = decltype(tag);
    const auto c = buildClusters<typename Cl::first_type, Cl::second_type::value>(L);
    constexpr int C = Cl::second_type::value;
    const double t = best([&] { cluster<typename Cl::first_type, C>(L, c, out); });
    std::printf("  %-14s %8.2f %11.2f in %12.1e\n", name, t * perPair, double(c.j.size()) * C * C / pairs,
                largestDifference(out, ref));
  };
  clusterRow(std::pair<double, std::integral_constant<int, 4>>{}, "cluster4 f64");
  clusterRow(std::pair<double, std::integral_constant<int, 8>>{}, "cluster8 f64");
  clusterRow(std::pair<float, std::integral_constant<int, 8>>{}, "cluster8 f32");
  clusterRow(std::pair<float, std::integral_constant<int, 16>>{}, "cluster16 f32");
  std::printf("# work per pair: li = listed neighbours, ca = candidates walked, in = interactions computed\n");
  std::printf("# vs scalar: largest |D - D_scalar| / max |D_scalar|\n");
  return 0;
}
