// The 3D speed yardstick: bench/yardstick_pairloop.cpp (the project's 2D
// yardstick) carried to three dimensions by this project, for the 3D rows of
// bench/speed_table.py. Not the product: "what 2 cores can do" with a plain,
// well-laid-out gather loop.
//
// The same step as the 2D yardstick, term for term: counting sort of the
// particles by cell and a permute of every field, then one pass of summation
// density (Wendland C2, sigma = 21 / (16 pi h^3) in 3D, Wendland 1995) with
// the Tait EOS p = B ((rho/rho0)^7 - 1), then one pass of forces (symmetric
// pressure, Monaghan's artificial viscosity alpha = 0.02, gravity), explicit
// Euler with reflecting floor and side walls. What changes with the
// dimension: a third coordinate per particle and per pair, a 3 x 3 x 3 cell
// stencil (27 cells instead of 9) and about (4/3 pi (2 h/dx)^3) neighbours
// instead of pi (2 h/dx)^2. Per neighbour the work is the 2D work plus one
// coordinate, so the ratio of sph's 3D speed to this yardstick's is
// comparable with the 2D ratio.
//
// Usage: sph-yardstick-3d [nx = 30] [steps = 50] [h/dx = 1.3]; the column is
// nx x nx x 2 nx particles. Prints N, threads, neighbours per particle,
// particle-steps per second (steps after the fifth) and ns per pair-thread.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>
#include <omp.h>

int main(int argc, char** argv) {
  const int nx = argc > 1 ? atoi(argv[1]) : 30;
  const int steps = argc > 2 ? atoi(argv[2]) : 50;
  const double hdx = argc > 3 ? atof(argv[3]) : 1.3;
  if (nx < 2 || steps < 6 || !(hdx > 0.5 && hdx < 4)) {
    fprintf(stderr, "usage: sph-yardstick-3d [nx >= 2] [steps >= 6] [h/dx in (0.5, 4)]\n");
    return 2;
  }
  const double dx = 0.01, h = hdx * dx, rc = 2 * h, rho0 = 1000, c0 = 40, g = 9.81, alpha = 0.02;
  const double sigma = 21.0 / (16.0 * M_PI * h * h * h), m = rho0 * dx * dx * dx, B = rho0 * c0 * c0 / 7;
  const int n = nx * nx * 2 * nx;
  std::vector<double> x(n), y(n), z(n), vx(n, 0), vy(n, 0), vz(n, 0), rho(n, rho0), p(n), ax(n), ay(n), az(n);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> jit(-0.05 * dx, 0.05 * dx);
  for (int i = 0, k = 0; i < nx; ++i)
    for (int j = 0; j < nx; ++j)
      for (int l = 0; l < 2 * nx; ++l, ++k) {
        x[k] = (i + 0.5) * dx + jit(rng);
        y[k] = (j + 0.5) * dx + jit(rng);
        z[k] = (l + 0.5) * dx + jit(rng);
      }
  const double L = nx * dx * 4, W = nx * dx, H = 2 * nx * dx * 1.2;
  const int cx = int(L / rc) + 1, cy = int(W / rc) + 1, cz = int(H / rc) + 1, cells = cx * cy * cz;
  auto cellOf = [&](double px, double py, double pz, int& a, int& b, int& c) {
    a = std::clamp(int(px / rc), 0, cx - 1);
    b = std::clamp(int(py / rc), 0, cy - 1);
    c = std::clamp(int(pz / rc), 0, cz - 1);
  };
  std::vector<int> cell(n), start(cells + 1), order(n), cnt(cells), pos(cells);
  std::vector<double> tx(n), ty(n), tz(n), tvx(n), tvy(n), tvz(n), trho(n);
  const double dt = 0.2 * h / c0;
  long long pairs = 0;
  double t_total = 0;
  for (int s = 0; s < steps; ++s) {
    auto t0 = std::chrono::steady_clock::now();
    std::fill(cnt.begin(), cnt.end(), 0);
    for (int i = 0; i < n; ++i) {
      int a, b, c;
      cellOf(x[i], y[i], z[i], a, b, c);
      cell[i] = (a * cy + b) * cz + c;
      cnt[cell[i]]++;
    }
    start[0] = 0;
    for (int c = 0; c < cells; ++c) start[c + 1] = start[c] + cnt[c];
    std::copy(start.begin(), start.end() - 1, pos.begin());
    for (int i = 0; i < n; ++i) order[pos[cell[i]]++] = i;
    for (int k = 0; k < n; ++k) {
      const int i = order[k];
      tx[k] = x[i]; ty[k] = y[i]; tz[k] = z[i];
      tvx[k] = vx[i]; tvy[k] = vy[i]; tvz[k] = vz[i];
      trho[k] = rho[i];
    }
    x.swap(tx); y.swap(ty); z.swap(tz); vx.swap(tvx); vy.swap(tvy); vz.swap(tvz); rho.swap(trho);
    // f(j) for every j in the 27 cells around particle i: the cells (a, b,
    // c-1..c+1) are contiguous in the sorted order, so 9 runs.
    auto forCandidates = [&](int i, auto&& f) {
      int a, b, c;
      cellOf(x[i], y[i], z[i], a, b, c);
      for (int da = -1; da <= 1; ++da) {
        const int aa = a + da;
        if (aa < 0 || aa >= cx) continue;
        for (int db = -1; db <= 1; ++db) {
          const int bb = b + db;
          if (bb < 0 || bb >= cy) continue;
          const int c0_ = (aa * cy + bb) * cz + std::max(c - 1, 0), c1_ = (aa * cy + bb) * cz + std::min(c + 1, cz - 1);
          for (int j = start[c0_]; j < start[c1_ + 1]; ++j) f(j);
        }
      }
    };
    long long pc = 0;
#pragma omp parallel for schedule(static) reduction(+ : pc)
    for (int i = 0; i < n; ++i) {
      double r_ = sigma * m;  // self
      forCandidates(i, [&](int j) {
        const double ddx = x[i] - x[j], ddy = y[i] - y[j], ddz = z[i] - z[j];
        const double r2 = ddx * ddx + ddy * ddy + ddz * ddz;
        if (r2 < rc * rc && j != i) {
          const double q = std::sqrt(r2) / h, u = 1 - 0.5 * q;
          r_ += m * sigma * u * u * u * u * (1 + 2 * q);
          ++pc;
        }
      });
      rho[i] = r_;
      p[i] = B * (std::pow(r_ / rho0, 7) - 1);
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      double fx = 0, fy = 0, fz = -g;
      const double pi_ = p[i] / (rho[i] * rho[i]);
      forCandidates(i, [&](int j) {
        const double ddx = x[i] - x[j], ddy = y[i] - y[j], ddz = z[i] - z[j];
        const double r2 = ddx * ddx + ddy * ddy + ddz * ddz;
        if (r2 < rc * rc && j != i) {
          const double r = std::sqrt(r2), q = r / h, u = 1 - 0.5 * q;
          const double dW = sigma * (-5.0 * q) * u * u * u / h;  // dW/dr
          double pij = pi_ + p[j] / (rho[j] * rho[j]);
          const double dvx = vx[i] - vx[j], dvy = vy[i] - vy[j], dvz = vz[i] - vz[j];
          const double vr = dvx * ddx + dvy * ddy + dvz * ddz;
          if (vr < 0) {
            const double mu = h * vr / (r2 + 0.01 * h * h);
            pij += -alpha * c0 * mu / (0.5 * (rho[i] + rho[j]));
          }
          const double f = -m * pij * dW / r;
          fx += f * ddx;
          fy += f * ddy;
          fz += f * ddz;
        }
      });
      ax[i] = fx;
      ay[i] = fy;
      az[i] = fz;
    }
    for (int i = 0; i < n; ++i) {
      vx[i] += ax[i] * dt; vy[i] += ay[i] * dt; vz[i] += az[i] * dt;
      x[i] += vx[i] * dt; y[i] += vy[i] * dt; z[i] += vz[i] * dt;
      if (z[i] < 0) { z[i] = 0; vz[i] = -vz[i]; }
      if (x[i] < 0) { x[i] = 0; vx[i] = -vx[i]; }
      if (y[i] < 0) { y[i] = 0; vy[i] = -vy[i]; }
      if (y[i] > W) { y[i] = W; vy[i] = -vy[i]; }
    }
    auto t1 = std::chrono::steady_clock::now();
    if (s >= 5) t_total += std::chrono::duration<double>(t1 - t0).count();
    pairs = pc;
  }
  const double ps = double(n) * (steps - 5) / t_total;
  printf("N=%d threads=%d neighbours=%.1f particle-steps/s=%.3g ns/pair=%.1f\n", n, omp_get_max_threads(),
         double(pairs) / n, ps, 1e9 * t_total / (double(pairs) * (steps - 5)) * omp_get_max_threads());
}
