// Gauss–Legendre against closed-form integrals: exact for degree ≤ 2n − 1 (monomials), weights sum
// to 2, symmetric nodes; and the 5-point nodes against Abramowitz & Stegun Table 25.4.
#include "compensator/support/quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace roprec {
namespace {

TEST(Quadrature, GaussLegendreIsExactToDegreeTwoNMinusOne) {
  for (const int n : {1, 2, 5, 12, 24, 48}) {
    std::vector<double> x;
    std::vector<double> w;
    gaussLegendre(n, x, w);
    ASSERT_EQ(static_cast<int>(x.size()), n);
    for (int d = 0; d <= 2 * n - 1 && d <= 60; ++d) {
      double q = 0;
      for (int i = 0; i < n; ++i)
        q += w[static_cast<size_t>(i)] * std::pow(x[static_cast<size_t>(i)], d);
      const double exact = d % 2 ? 0.0 : 2.0 / (d + 1);
      EXPECT_NEAR(q, exact, 1e-13) << "n " << n << " degree " << d;
    }
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(x[static_cast<size_t>(i)], -x[static_cast<size_t>(n - 1 - i)], 1e-15);
  }
  std::vector<double> x;
  std::vector<double> w;
  gaussLegendre(5, x, w);
  EXPECT_NEAR(x[4], 0.906179845938664, 1e-15);  // A&S Table 25.4
  EXPECT_NEAR(w[4], 0.236926885056189, 1e-15);
  EXPECT_NEAR(x[2], 0.0, 1e-16);
  EXPECT_NEAR(w[2], 0.568888888888889, 1e-15);
}

}  // namespace
}  // namespace roprec
