// Provenance: the project's speed yardstick, shared/bench/pairloop.cpp (written by this project's team),
// copied unchanged below so that benchmarks run from a clone. Built as sph-yardstick (-O3 -fopenmp).
// Roofline probe: a plain, well-laid-out 2D WCSPH step (Wendland C2, Tait EOS, Monaghan AV, gravity),
// cell-sorted particles, gather form, OpenMP. Not the product: a yardstick for "what 2 cores can do".
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
#include <vector>
#include <omp.h>

int main(int argc, char** argv) {
  const int nx = argc > 1 ? atoi(argv[1]) : 150;          // particles per side of the column
  const int steps = argc > 2 ? atoi(argv[2]) : 50;
  const double hdx = argc > 3 ? atof(argv[3]) : 1.3;       // h / dx
  const double dx = 0.01, h = hdx * dx, rc = 2 * h, rho0 = 1000, c0 = 40, g = 9.81, alpha = 0.02;
  const double sigma = 7.0 / (4.0 * M_PI * h * h), m = rho0 * dx * dx, B = rho0 * c0 * c0 / 7;
  const int n = nx * 2 * nx;
  std::vector<double> x(n), y(n), vx(n, 0), vy(n, 0), rho(n, rho0), p(n), ax(n), ay(n);
  std::mt19937 rng(1); std::uniform_real_distribution<double> jit(-0.05 * dx, 0.05 * dx);
  for (int i = 0, k = 0; i < nx; ++i) for (int j = 0; j < 2 * nx; ++j, ++k) { x[k] = (i + 0.5) * dx + jit(rng); y[k] = (j + 0.5) * dx + jit(rng); }
  const double L = nx * dx * 4, H = 2 * nx * dx * 1.2;
  const int cx = int(L / rc) + 1, cy = int(H / rc) + 1;
  std::vector<int> cell(n), start(cx * cy + 1), order(n), cnt(cx * cy);
  std::vector<double> tx(n), ty(n), tvx(n), tvy(n), trho(n);
  const double dt = 0.2 * h / c0;
  long long pairs = 0;
  double t_total = 0;
  for (int s = 0; s < steps; ++s) {
    auto t0 = std::chrono::steady_clock::now();
    // counting sort by cell, permute all fields
    std::fill(cnt.begin(), cnt.end(), 0);
    for (int i = 0; i < n; ++i) { int a = std::clamp(int(x[i] / rc), 0, cx - 1), b = std::clamp(int(y[i] / rc), 0, cy - 1); cell[i] = a * cy + b; cnt[cell[i]]++; }
    start[0] = 0; for (int c = 0; c < cx * cy; ++c) start[c + 1] = start[c] + cnt[c];
    std::vector<int> pos(start.begin(), start.end() - 1);
    for (int i = 0; i < n; ++i) order[pos[cell[i]]++] = i;
    for (int k = 0; k < n; ++k) { int i = order[k]; tx[k] = x[i]; ty[k] = y[i]; tvx[k] = vx[i]; tvy[k] = vy[i]; trho[k] = rho[i]; }
    x.swap(tx); y.swap(ty); vx.swap(tvx); vy.swap(tvy); rho.swap(trho);
    long long pc = 0;
    // density
    #pragma omp parallel for schedule(static) reduction(+:pc)
    for (int i = 0; i < n; ++i) {
      int a = std::clamp(int(x[i] / rc), 0, cx - 1), b = std::clamp(int(y[i] / rc), 0, cy - 1);
      double r_ = sigma * m;  // self
      for (int da = -1; da <= 1; ++da) { int aa = a + da; if (aa < 0 || aa >= cx) continue;
        int c0_ = aa * cy + std::max(b - 1, 0), c1_ = aa * cy + std::min(b + 1, cy - 1);
        for (int j = start[c0_]; j < start[c1_ + 1]; ++j) {
          double ddx = x[i] - x[j], ddy = y[i] - y[j], r2 = ddx * ddx + ddy * ddy;
          if (r2 < rc * rc && j != i) { double q = std::sqrt(r2) / h, u = 1 - 0.5 * q; r_ += m * sigma * u * u * u * u * (1 + 2 * q); ++pc; }
        } }
      rho[i] = r_; p[i] = B * (std::pow(r_ / rho0, 7) - 1);
    }
    // forces
    #pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      int a = std::clamp(int(x[i] / rc), 0, cx - 1), b = std::clamp(int(y[i] / rc), 0, cy - 1);
      double fx = 0, fy = -g; const double pi_ = p[i] / (rho[i] * rho[i]);
      for (int da = -1; da <= 1; ++da) { int aa = a + da; if (aa < 0 || aa >= cx) continue;
        int c0_ = aa * cy + std::max(b - 1, 0), c1_ = aa * cy + std::min(b + 1, cy - 1);
        for (int j = start[c0_]; j < start[c1_ + 1]; ++j) {
          double ddx = x[i] - x[j], ddy = y[i] - y[j], r2 = ddx * ddx + ddy * ddy;
          if (r2 < rc * rc && j != i) {
            double r = std::sqrt(r2), q = r / h, u = 1 - 0.5 * q;
            double dW = sigma * (-5.0 * q) * u * u * u / h;          // dW/dr
            double pij = pi_ + p[j] / (rho[j] * rho[j]);
            double dvx = vx[i] - vx[j], dvy = vy[i] - vy[j], vr = dvx * ddx + dvy * ddy;
            if (vr < 0) { double mu = h * vr / (r2 + 0.01 * h * h); pij += -alpha * c0 * mu / (0.5 * (rho[i] + rho[j])); }
            double f = -m * pij * dW / r; fx += f * ddx; fy += f * ddy;
          } } }
      ax[i] = fx; ay[i] = fy;
    }
    for (int i = 0; i < n; ++i) { vx[i] += ax[i] * dt; vy[i] += ay[i] * dt; x[i] += vx[i] * dt; y[i] += vy[i] * dt;
      if (y[i] < 0) { y[i] = 0; vy[i] = -vy[i]; } if (x[i] < 0) { x[i] = 0; vx[i] = -vx[i]; } }
    auto t1 = std::chrono::steady_clock::now();
    if (s >= 5) t_total += std::chrono::duration<double>(t1 - t0).count();
    pairs = pc;
  }
  double ps = double(n) * (steps - 5) / t_total;
  printf("N=%d threads=%d neighbours=%.1f particle-steps/s=%.3g ns/pair=%.1f\n", n, omp_get_max_threads(), double(pairs) / n, ps,
         1e9 * t_total / (double(pairs) * (steps - 5)) * omp_get_max_threads());
}
