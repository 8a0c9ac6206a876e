// Colour-field surface tension, the continuum surface force (CSF) of
// Brackbill, Kothe & Zemach 1992 in SPH: Mueller, Charypar & Gross 2003,
// "Particle-based fluid simulation for interactive applications", SCA,
// sec. 4.4 (seed document 002), and Morris 2000, "Simulating surface tension
// with smoothed particle hydrodynamics", Int. J. Numer. Meth. Fluids 33, 333:
//
//   c_i     = sum_j (m_j / rho_j) chi_j W(r_ij)                  colour field
//   n_i     = grad c_i = sum_j (m_j / rho_j) chi_j grad_i W(r_ij)
//   f_i     = sigma kappa_i n_i        where |n_i| > threshold / h, else 0
//   a_i    += f_i / rho_i
//
// with the curvature kappa_i by one of three methods (surface_tension = ...):
//   muller  kappa_i = - lap c_i / |n_i|,  lap c_i = sum_j (m_j/rho_j) chi_j lap W(r_ij)
//           (j = i included), so f_i = - sigma lap c_i n_i / |n_i| (Mueller eq. 19)
//   morris  kappa_i = - div(n/|n|)_i
//                   = - sum_j V_j (nhat_j - nhat_i) . grad_i W_ij / sum_j V_j W_ij
//           over the neighbours j (and i) with a reliable normal, |n_j| > threshold/h
//           (Morris 2000, eqs. 20-22: the divergence of the unit normal,
//           normalised by the kernel sum of the particles that have one).
//   corrected  Morris's, with the kernel-gradient correction in n and in the
//           divergence, and the force over the whole band (two phases):
//           terms/corrected_surface_tension.hpp has its equations.
//
// chi_j is the particle's colour (the `colour` field): 1 in the phase whose
// surface has tension, 0 in the other (colour_box_*, colour_ellipse_*); with
// neither every fluid particle has chi = 1 and the surface is the free
// surface. n points into the coloured phase, kappa > 0 on a convex drop,
// and f pulls the surface towards its centre of curvature.
//
// Kernels: with the Mueller set, c, n and lap c use poly6 and its own
// gradient and Laplacian, as in the paper ("poly6 in all but two cases"):
//   grad W = -6 C r_ij (h^2 - r^2)^2,  lap W = 6 C (h^2 - r^2) (4 r^2 - D (h^2 - r^2)),
//   C = 4/(pi h^8) (2D), 315/(64 pi h^9) (3D)
// (3D: -945/(32 pi h^9) (h^2 - r^2)(3 h^2 - 7 r^2), the paper's). Any other
// kernel uses its own normalised W, grad W and lap W (kernels/*.hpp).
//
// The two curvatures differ where it matters. Across an interface n is the
// gradient of a smoothed step, |n| a bump of width ~ the support. Mueller's
// -lap c / |n| is kappa + (d|n|/dd)/|n|: kappa where |n| peaks, but +-1/h on
// either side, so its force is sigma kappa n plus a dipole of order sigma/h^2
// that pulls the two sides of the interface apart (it integrates to zero
// across a two-phase interface, so the Laplace jump survives, but it makes
// pressure waves of order sigma/h, far above sigma/R when R >> h). At a
// free surface (no colour region) the dipole does not cancel and adds an
// inward pull of order sigma/h whatever the curvature. Morris's divergence
// of the unit normal is kappa across the whole band, and his force has no
// dipole. Measured in docs/methods/surface-tension.md.
//
// Pass structure: a pre-pass (ColourFieldPass) computes n and kappa for the
// fluid particles from their fluid neighbours (walls carry no colour: a
// coloured phase touching a wall sees a surface there); the force pass
// adds f_i / rho_i in its epilogue, per particle.
#pragma once

#include "sph/kernels/kernels.hpp"
#include "sph/models/wcsph_choices.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/terms/corrected_surface_tension.hpp"
#include "sph/terms/term_bits.hpp"

#include <cmath>

namespace sph {

// The kernel the colour field uses, as (W, (dW/dr)/r, lap W) of r: the
// kernel's own, or poly6 for the Mueller set.
template <class Kernel>
struct ColourKernel {
  Kernel k;
  Real W(Real r) const { return k.W(r); }
  Real dWdr_r(Real r) const { return r > 0 ? k.dWdr_r(r) : 0; }
  Real laplacian(Real r) const { return k.laplacianW(r); }
};

template <int D>
struct ColourKernel<Muller<D>> {
  Muller<D> k;
  Real W(Real r) const { return k.W(r); }
  // poly6 = C s^3 with s = h^2 - r^2, and C = poly6(0) / h^6.
  Real dWdr_r(Real r) const {
    if (r >= k.h()) return 0;
    const Real s = k.h() * k.h() - r * r;
    return -6 * c6() * s * s;
  }
  Real laplacian(Real r) const {
    if (r >= k.h()) return 0;
    const Real s = k.h() * k.h() - r * r;
    return 6 * c6() * s * (4 * r * r - D * s);
  }
  Real c6() const {
    const Real h2 = k.h() * k.h();
    return k.W(0) / (h2 * h2 * h2);
  }
};

// kCorrected: terms/corrected_surface_tension.hpp (the kernel-gradient-
// corrected normal and divergence, the force over the whole band).
// (CurvatureMethod: models/wcsph_choices.hpp.)

// n_i and kappa_i for every fluid particle i (fluid neighbours only).
// twoPhase (a colour region was given): the difference forms
//   n_i = sum_j V_j (chi_j - chi_i) grad W_ij,  lap c_i = sum_j V_j (chi_j - chi_i) lap W_ij,
// which are the same sums up to sum_j V_j grad W_ij and sum_j V_j lap W_ij,
// zero in the continuum but not on a disordered (or any) lattice: the
// difference form is exactly 0 in the bulk of either phase, where the plain
// sum carries noise of order 0.1/h at 10% disorder. At a free surface (no
// colour region: chi = 1 everywhere) the plain sums are the only ones that
// see the surface, so they are used there (and kCorrected is kMorris there).
// r_ij = x_i - x_j (a neighbour across a periodic face is a ghost).
template <int D, class Kernel>
void computeColourField(Particles<D>& P, const NeighbourList<D>& neighbours, const Kernel& kernel,
                        CurvatureMethod method, Real minNormal, bool twoPhase) {
  const ColourKernel<Kernel> W{kernel};
  const std::size_t n = P.fluidCount();
  const Real lap0 = W.laplacian(0), W0 = W.W(0);
  const bool muller = method == CurvatureMethod::kMuller;
  const bool corrected = method == CurvatureMethod::kCorrected && twoPhase;
#pragma omp parallel if (n >= kMinParallelSize)
  {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<D> xi = P.x[i];
      const Real base = twoPhase ? P.colour[i] : 0;
      Vec<D> normal = Vec<D>::Zero();
      Mat<D> M = Mat<D>::Zero();  // corrected: sum_j V_j (x_j - x_i) (x) grad_i W_ij
      Real lap = (P.colour[i] - base) * P.m[i] / P.rho[i] * lap0;
      neighbours.forEachByKind(
          i,
          [&](std::uint32_t j) {
            const Real dchi = P.colour[j] - base;
            if (dchi == 0 && !corrected) return;
            const Vec<D> rij = xi - P.x[j];
            const Real r = rij.norm();
            const Real Vj = P.m[j] / P.rho[j];
            const Real g = W.dWdr_r(r);
            if (corrected) M.noalias() -= (Vj * g) * (rij * rij.transpose());
            if (dchi == 0) return;
            normal += (dchi * Vj * g) * rij;
            if (muller) lap += dchi * Vj * W.laplacian(r);
          },
          [](std::uint32_t) {});
      if (corrected && !normal.isZero()) normal = correctedGradient<D>(M, normal);
      P.colourNormal[i] = normal;
      const Real norm = normal.norm();
      if (muller) P.curvature[i] = norm > minNormal ? -lap / norm : 0;
    }
    // Morris (and corrected): the divergence of the unit normal, over the
    // particles that have a reliable one (the loop above has finished: omp
    // for's barrier), the ghosts' and halos' normals copied from their
    // sources.
    if (!muller) {
      P.refreshGhostsAndHalosInTeam(fieldBit(kFieldColourNormal));
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        const Real ni = P.colourNormal[i].norm();
        if (!(ni > minNormal)) {
          P.curvature[i] = 0;
          continue;
        }
        const Vec<D> xi = P.x[i], nhat_i = P.colourNormal[i] / ni;
        Real div = 0, shepard = P.m[i] / P.rho[i] * W0;
        Mat<D> G = Mat<D>::Zero(), Mr = Mat<D>::Zero();
        neighbours.forEachByKind(
            i,
            [&](std::uint32_t j) {
              const Real nj = P.colourNormal[j].norm();
              if (!(nj > minNormal)) return;
              const Vec<D> rij = xi - P.x[j];
              const Real r = rij.norm();
              const Real Vj = P.m[j] / P.rho[j];
              const Real g = W.dWdr_r(r);
              const Vec<D> dn = P.colourNormal[j] / nj - nhat_i;
              div += Vj * g * dn.dot(rij);
              shepard += Vj * W.W(r);
              if (corrected) {
                G.noalias() += (Vj * g) * (dn * rij.transpose());
                Mr.noalias() -= (Vj * g) * (rij * rij.transpose());
              }
            },
            [](std::uint32_t) {});
        P.curvature[i] = corrected ? correctedCurvature<D>(G, Mr, -div / shepard) : -div / shepard;
      }
      // Corrected: the band's tails (0 < |n| <= minNormal) take the kernel
      // mean of their reliable neighbours' kappa, so that the force acts on
      // the whole of the colour gradient.
      if (corrected) {
        P.refreshGhostsAndHalosInTeam(fieldBit(kFieldCurvature));
#pragma omp for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
          const Real ni = P.colourNormal[i].norm();
          if (ni > minNormal || !(ni > 0)) continue;
          const Vec<D> xi = P.x[i];
          Real sum = 0, weight = 0;
          neighbours.forEachByKind(
              i,
              [&](std::uint32_t j) {
                if (!(P.colourNormal[j].norm() > minNormal)) return;
                const Real w = P.m[j] / P.rho[j] * W.W(Vec<D>(xi - P.x[j]).norm());
                sum += w * P.curvature[j];
                weight += w;
              },
              [](std::uint32_t) {});
          P.curvature[i] = weight > 0 ? sum / weight : 0;
        }
      }
    }
  }
}

// The force of the epilogue: a_i += sigma kappa_i n_i / rho_i where
// |n_i| > minNormal (= threshold / h; 0 for the corrected method, whose
// kappa is 0 where n carries no curvature).
template <int D>
struct ColourSurfaceTension {
  static constexpr unsigned bit = term_bits::kSurfaceTension;
  Real sigma = 0;
  Real minNormal = 0;

  // The fields acceleration() reads.
  static constexpr FieldSet kReads = fieldBits(kFieldColourNormal, kFieldCurvature, kFieldRho);

  Vec<D> acceleration(std::size_t i, const Particles<D>& P) const {
    const Vec<D>& n = P.colourNormal[i];
    if (!(n.squaredNorm() > minNormal * minNormal)) return Vec<D>::Zero();
    return (sigma * P.curvature[i] / P.rho[i]) * n;
  }
};

}  // namespace sph
