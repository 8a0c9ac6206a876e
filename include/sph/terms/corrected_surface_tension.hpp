// Corrected colour-field surface tension (surface_tension = "corrected"):
// Morris's continuum surface force (Morris 2000, Int. J. Numer. Meth. Fluids
// 33, 333, eqs. 17-22; Brackbill, Kothe & Zemach 1992) with the kernel
// gradient correction of Bonet & Lok 1999 (Comput. Methods Appl. Mech.
// Engrg. 180, 97, eq. 29; Randles & Libersky 1996) in both of its
// derivatives, and the force spread over the whole interface band:
//
//   M_i     = sum_j V_j (x_j - x_i) (x) grad_i W_ij           (all fluid j)
//   n_i     = M_i^-1 sum_j V_j (chi_j - chi_i) grad_i W_ij     corrected colour gradient
//   kappa_i = - tr( sum_j V_j (nhat_j - nhat_i) (x) grad_i W_ij  Mr_i^-1 )
//             Mr_i = sum_j V_j (x_j - x_i) (x) grad_i W_ij over the j with |n_j| > eps/h
//             (the corrected divergence of the unit normal, over the reliable normals)
//   kappa_i = sum_j V_j kappa_j W_ij / sum_j V_j W_ij  over reliable j, where 0 < |n_i| <= eps/h
//   f_i     = sigma kappa_i n_i  wherever n_i != 0,  a_i += f_i / rho_i
//
// Why (measured, docs/validation/surface-tension.md): the pressure jump a CSF force
// makes across an interface is sigma kappa times the integral of |n| along
// the normal, which must be 1 (n is the gradient of a unit step). With the
// plain kernel sum and the force cut at |n| > eps/h (the `morris` method)
// that integral was 0.92 in the square-drop case (0.97 from the plain sum on
// a disordered set, less 5% for the tails under the threshold), so the
// Laplace jump came out 0.91 sigma/R and fell with resolution (0.89 at
// R/dx 18). M_i^-1 makes the gradient exact for a linear colour field on any
// particle set, and on a lattice sum_i V_i n_i across a flat interface is
// then exactly 1 (the cross-pair double sum and the first moment are the
// same lattice sum); spreading kappa onto the band's tails keeps their share
// of the integral. The divergence of nhat is corrected with the moment of
// the reliable particles only (Morris normalises by their kernel sum,
// sum V_j W_ij, which is the right weight for a value, not for a
// derivative); its trace-only form, d sum V (nhat_i - nhat_j).grad W /
// sum V (x_i - x_j).grad W (Adami, Hu & Adams 2010, eq. 20, over the same
// particles), gave kappa R = 1.23: the band is narrow across the interface
// and wide along it, so the moment is anisotropic and its trace is not the
// tangential moment the divergence needs.
//
// Guards: where the smallest eigenvalue of M_i is below kCorrectedMinEigenvalue
// (a particle near a wall or a free surface: the colour pass sums over fluid
// neighbours only) the colour gradient is left uncorrected; where that of
// Mr_i is below kCorrectedMinBandEigenvalue, kappa falls back to Morris's
// normalisation. Two phases
// only (a colour region given): at a free surface chi is 1 on every
// particle, the corrected gradient of a constant is 0, so there the plain
// sums of `morris` are used.
#pragma once

#include "sph/types.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace sph {

constexpr Real kCorrectedMinEigenvalue = 0.2;       // M_i (a full support: ~1)
constexpr Real kCorrectedMinBandEigenvalue = 0.05;  // Mr_i (the band only: ~0.3 across it)

// M^-1 v, or v when M is ill-conditioned (smallest eigenvalue below the guard).
template <int D>
inline Vec<D> correctedGradient(const Mat<D>& M, const Vec<D>& v) {
  Eigen::SelfAdjointEigenSolver<Mat<D>> eig;
  eig.computeDirect(M, Eigen::EigenvaluesOnly);
  if (!(eig.eigenvalues()[0] >= kCorrectedMinEigenvalue)) return v;
  return M.inverse() * v;
}

// -tr(G Mr^-1): minus the corrected divergence of the unit normal, from
// G = sum_j V_j (nhat_j - nhat_i) (x) grad_i W_ij and Mr (both over the
// reliable neighbours); `fallback` (Morris's curvature) when Mr is
// ill-conditioned.
template <int D>
inline Real correctedCurvature(const Mat<D>& G, const Mat<D>& Mr, Real fallback) {
  Eigen::SelfAdjointEigenSolver<Mat<D>> eig;
  eig.computeDirect(Mr, Eigen::EigenvaluesOnly);
  if (!(eig.eigenvalues()[0] >= kCorrectedMinBandEigenvalue)) return fallback;
  return -(G * Mr.inverse()).trace();
}

}  // namespace sph
