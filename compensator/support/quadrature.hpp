#pragma once
/// \file quadrature.hpp
/// Gauss–Legendre quadrature: ∫₋₁¹ f ≈ Σ wᵢ f(xᵢ), exact for polynomials of degree ≤ 2n − 1.
/// Nodes are the roots of P_n found by Newton from the Tricomi estimate cos(π(i + 3/4)/(n + 1/2)),
/// weights wᵢ = 2 / ((1 − xᵢ²) P_n'(xᵢ)²) (Abramowitz & Stegun 25.4.29). Ascending order.

#include <vector>

namespace roprec {

void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w);

}  // namespace roprec
