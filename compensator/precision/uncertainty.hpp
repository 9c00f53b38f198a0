#pragma once
/// \file uncertainty.hpp
/// GUM arithmetic used by the per-hole budget (docs/process.md §5; JCGM 100:2008, ISO 9283,
/// ISO 14253-1). All values SI (m).
///
/// * ISO 9283 pose repeatability RP = l̄ + 3 S_l of the 3-D distances to the barycentre. For an
///   isotropic Gaussian scatter with σ per axis, l follows a chi distribution with 3 degrees of
///   freedom: l̄ = 2√(2/π) σ = 1.5958 σ, S_l = √(3 − 8/π) σ = 0.6734 σ, so RP = 3.6160 σ.
/// * 2-D radial coverage: the radius r of a zero-mean bivariate normal with covariance Σ
///   (eigenvalues λ₁ ≤ λ₂) satisfies, with the major coordinate z₂ = (R/√λ₂) sin t,
///   P(r ≤ R) = 2∫₀^{π/2} φ(R sin t/√λ₂) erf(R cos t/√(2λ₁)) (R/√λ₂) cos t dt (φ the standard
///   normal density) — smooth for any aspect ratio, 48-point Gauss–Legendre; for λ₁ = λ₂ = u² it
///   is Rayleigh, R₉₅ = √(−2 ln 0.05) u = 2.4477 u; for λ₁ → 0 the 1-D quantile 1.960 √λ₂. Do not
///   use k = 2 on a radius (docs/process.md §5.1).

#include <Eigen/Core>

namespace roprec {

/// σ per axis from an ISO 9283 RP (3-D, isotropic Gaussian): RP / 3.6160.
double sigmaFromRp(double rp);
/// RP of an isotropic Gaussian with σ per axis (the inverse).
double rpFromSigma(double sigma);
/// Rayleigh coverage factor k such that P(r ≤ k u) = p (2-D isotropic): √(−2 ln(1 − p)).
double rayleighCoverageFactor(double p = 0.95);
/// P(r ≤ R) for a zero-mean 2-D normal with covariance Σ (2×2, SPSD).
double radialProbability(const Eigen::Matrix2d& Sigma, double R);
/// The radius R with P(r ≤ R) = p: safeguarded Newton (P and dP/dR share the precomputed nodes'
/// exponentials) inside the bracket of the 1-D and the Rayleigh quantile of the major axis,
/// from their interpolation in √(l1/l2); closed-form 2×2 eigenvalues. Relative accuracy ~1e-13.
/// For p = 0.95 (every prediction) R/√l2 is a function of √(l1/l2) alone: it is tabulated by
/// that solver (1,025 points, compiled in: coverage_table95.hpp) and interpolated (cubic,
/// ≤ 1e-9 relative) for l1/l2 ≥ 1e-3.
double radialCoverage(const Eigen::Matrix2d& Sigma, double p = 0.95);
/// The solver alone (eigenvalues 0 ≤ l1 ≤ l2 given, no table): what the table holds at
/// l1 = t², l2 = 1, p = 0.95 (tests/coverage_table_test.cpp checks and can rewrite it).
double radialCoverageSolved(double l1, double l2, double p);

}  // namespace roprec
