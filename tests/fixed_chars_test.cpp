#include "compensator/support/fixed_chars.hpp"

#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace roprec {
namespace {

/// The reference: libstdc++'s std::to_chars (exact, round half to even), independent of the
/// fast path under test.
std::string reference(double v, int decimals) {
  std::array<char, 512> buf{};
  const auto r =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::fixed, decimals);
  EXPECT_EQ(r.ec, std::errc());
  return {buf.data(), r.ptr};
}

std::string fast(double v, int decimals) {
  std::array<char, 512> buf{};
  const auto r = toFixedChars(buf.data(), buf.data() + buf.size(), v, decimals);
  EXPECT_EQ(r.ec, std::errc());
  return {buf.data(), r.ptr};
}

void expectSame(double v, int decimals) {
  ASSERT_EQ(fast(v, decimals), reference(v, decimals))
      << "v = " << std::hexfloat << v << ", decimals " << decimals;
}

TEST(FixedChars, ExactTiesRoundHalfToEvenAsToChars) {
  // exact binary ties: the fast path must hand them to std::to_chars
  for (const double v : {0.5, 1.5, 2.5, 0.125, 0.375, 0.625, 1.0625, -0.5, -2.5, 1234.5625}) {
    for (int d = 0; d <= 6; ++d) expectSame(v, d);
  }
  EXPECT_EQ(fast(2.5, 0), "2");
  EXPECT_EQ(fast(3.5, 0), "4");
  EXPECT_EQ(fast(0.125, 2), "0.12");
  EXPECT_EQ(fast(0.375, 2), "0.38");
  // not ties, though their product with 10 rounds onto one: 0.35 is 0.34999999999999997…
  EXPECT_EQ(10 * 0.35, 3.5);
  EXPECT_EQ(fast(0.35, 1), "0.3");
  EXPECT_EQ(fast(0.05, 1), "0.1");
}

TEST(FixedChars, DecimalLookingTiesFollowTheBinaryValue) {
  // 0.0005, 1.0005, 2.675: not ties in binary; the exact value decides
  for (const double v :
       {0.0005, 1.0005, 2.675, 1.005, 0.045, 1e-3, 123.4565, 0.1, 0.7, 9.995, 0.05, 0.35}) {
    for (int d = 0; d <= 17; ++d) {
      expectSame(v, d);
      expectSame(-v, d);
    }
  }
}

TEST(FixedChars, SignsZerosAndCarries) {
  for (int d = 0; d <= 9; ++d) {
    expectSame(0.0, d);
    expectSame(-0.0, d);
    expectSame(-1e-12, d);        // rounds to "-0.000…" as std::to_chars writes it
    expectSame(9.9999999999, d);  // the carry adds a digit
    expectSame(-99.99999999, d);
    expectSame(0.999999999999, d);
  }
  EXPECT_EQ(fast(-0.0, 3), "-0.000");
  EXPECT_EQ(fast(9.9996, 3), "10.000");
  EXPECT_EQ(fast(-0.0004, 3), "-0.000");
  EXPECT_EQ(fast(42.0, 0), "42");
}

TEST(FixedChars, EdgesOfTheFastPathAndBeyondIt) {
  for (int d = 0; d <= 20; ++d) {
    const double p = std::pow(10.0, d);
    for (const double r : {0x1p52, 0x1p52 - 1, 0x1p52 + 2, 0x1p53, 0x1p51 + 0.5, 1e17, 1e22}) {
      expectSame(r / p, d);
      expectSame(-r / p, d);
      expectSame(std::nextafter(r / p, 0.0), d);
      expectSame(std::nextafter(r / p, 1e300), d);
    }
  }
  for (const double v : {1e300, -1e300, std::numeric_limits<double>::max(),
                         std::numeric_limits<double>::denorm_min(), 5e-324, 1e-310}) {
    for (const int d : {0, 3, 17, 25, 60}) expectSame(v, d);
  }
}

TEST(FixedChars, NonFiniteValuesAsToChars) {
  for (const int d : {0, 3}) {
    expectSame(std::numeric_limits<double>::infinity(), d);
    expectSame(-std::numeric_limits<double>::infinity(), d);
    expectSame(std::numeric_limits<double>::quiet_NaN(), d);
  }
}

TEST(FixedChars, SeededRandomValuesOfEveryMagnitudeMatchToChars) {
  std::mt19937_64 rng(20261125);
  std::uniform_int_distribution<int> dec(0, 19);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-30, 25);
  std::uniform_int_distribution<std::uint64_t> bits;
  for (int i = 0; i < 400000; ++i) {
    const int d = dec(rng);
    expectSame(std::ldexp(mant(rng), expo(rng)), d);  // roprec's scales: mm, µm, rad, N
    // numbers with few decimals, as programs and cards write them, then perturbed by an ulp
    const double q = std::round(mant(rng) * 1e7) / 1e4;
    expectSame(q, d);
    expectSame(std::nextafter(q, 1e9), d);
    expectSame(std::nextafter(q, -1e9), d);
    if (i % 8 == 0) {  // any bit pattern
      const auto b = bits(rng);
      double v = 0;
      static_assert(sizeof v == sizeof b);
      std::memcpy(&v, &b, sizeof v);
      expectSame(v, d);
    }
    if (HasFailure()) return;  // the first value that differs is enough
  }
}

TEST(FixedChars, TooSmallABufferIsAnErrorLikeToChars) {
  std::array<char, 4> buf{};
  const auto r = toFixedChars(buf.data(), buf.data() + buf.size(), 123.456, 3);
  EXPECT_EQ(r.ec, std::errc::value_too_large);
  EXPECT_EQ(r.ptr, buf.data() + buf.size());
  const auto ok = toFixedChars(buf.data(), buf.data() + buf.size(), 1.25, 2);
  ASSERT_EQ(ok.ec, std::errc());
  EXPECT_EQ(std::string(buf.data(), ok.ptr), "1.25");
}

TEST(AppendFixed, NoSignOnAZeroAndToCharsTextOtherwise) {
  std::string s = "x=";
  appendFixed(s, -0.0004, 3);
  EXPECT_EQ(s, "x=0.000");
  s.clear();
  appendFixed(s, -0.0, 0);
  EXPECT_EQ(s, "0");
  s.clear();
  appendFixed(s, -0.0006, 3);
  EXPECT_EQ(s, "-0.001");
  s.clear();
  appendFixed(s, -std::numeric_limits<double>::infinity(), 3);
  EXPECT_EQ(s, "-inf");
  s.clear();
  appendFixed(s, -std::numeric_limits<double>::max(), 80);  // places clamped to 60
  EXPECT_EQ(s, reference(-std::numeric_limits<double>::max(), 60));
  s.clear();
  appendFixed(s, 2.5, -3);  // and to 0
  EXPECT_EQ(s, "2");
}

}  // namespace
}  // namespace roprec
