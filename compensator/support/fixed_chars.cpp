#include "compensator/support/fixed_chars.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace roprec {

namespace {

constexpr int kMaxFastDecimals = 17;

/// 10^d for d = 0 … kMaxFastDecimals, each exact in a double (10^d is exact up to d = 22).
constexpr std::array<double, kMaxFastDecimals + 1> kPow10 = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,
                                                             1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                                             1e12, 1e13, 1e14, 1e15, 1e16, 1e17};

/// 10^d as integers, d = 0 … 19.
constexpr std::array<std::uint64_t, 20> kPow10Int = [] {
  std::array<std::uint64_t, 20> t{};
  std::uint64_t p = 1;
  for (std::uint64_t& x : t) {
    x = p;
    p *= 10;
  }
  return t;
}();

/// "00" "01" … "99": two digits at a time.
constexpr std::array<char, 200> kDigitPairs = [] {
  std::array<char, 200> t{};
  for (std::size_t i = 0; i < 100; ++i) {
    t[2 * i] = static_cast<char>('0' + i / 10);
    t[2 * i + 1] = static_cast<char>('0' + i % 10);
  }
  return t;
}();

/// The number of decimal digits of m (0 for 0).
int digitCount(std::uint64_t m) {
  // bit_width · log10(2) ≈ bit_width · 1233 / 4096, one short at most below a power of ten
  const int guess = (std::bit_width(m) * 1233) >> 12;
  return guess + (m >= kPow10Int[static_cast<std::size_t>(guess)] ? 1 : 0);
}

/// Writes m's last `count` digits so that they end at `end` and removes them from m.
void writeDigits(char* end, std::uint64_t& m, int count) {
  for (; count >= 2; count -= 2) {
    end -= 2;
    std::memcpy(end, &kDigitPairs[static_cast<std::size_t>(m % 100) * 2], 2);
    m /= 100;
  }
  if (count == 1) {
    *--end = static_cast<char>('0' + m % 10);
    m /= 10;
  }
}

}  // namespace

std::to_chars_result toFixedChars(char* first, char* last, double v, int decimals) {
  if (decimals < 0 || decimals > kMaxFastDecimals)
    return std::to_chars(first, last, v, std::chars_format::fixed, decimals);
  const double r = std::fabs(v) * kPow10[static_cast<std::size_t>(decimals)];
  // below 2^52: the integer part and r minus it are exact, and m + 1 still fits the mantissa
  if (!(r < 0x1p52)) return std::to_chars(first, last, v, std::chars_format::fixed, decimals);
  const auto whole = static_cast<std::uint64_t>(r);
  const double frac = r - static_cast<double>(whole);
  // whole + 0.5 is a double: rounding is monotone, so v·10^d lies on the same side of it as r
  // does, unless r is on it (a tie, or a product rounded onto it)
  if (frac == 0.5) return std::to_chars(first, last, v, std::chars_format::fixed, decimals);
  std::uint64_t m = whole + (frac > 0.5 ? 1U : 0U);
  // [-]integer digits[.decimals digits]
  const bool negative = std::signbit(v);
  const int int_digits = std::max(digitCount(m) - decimals, 1);
  const std::ptrdiff_t size = (negative ? 1 : 0) + int_digits + (decimals > 0 ? decimals + 1 : 0);
  if (last - first < size) return {last, std::errc::value_too_large};
  char* p = first + size;
  if (decimals > 0) {
    writeDigits(p, m, decimals);
    p -= decimals;
    *--p = '.';
  }
  writeDigits(p, m, int_digits);
  if (negative) *first = '-';
  return {first + size, std::errc()};
}

void appendFixed(std::string& out, double v, int decimals) {
  // DBL_MAX with 60 places: 309 + 1 + 60 characters and a sign; written before it is read
  std::array<char, 400> buf;  // NOLINT(cppcoreguidelines-pro-type-member-init)
  const auto r = toFixedChars(buf.data(), buf.data() + buf.size(), v, std::clamp(decimals, 0, 60));
  const char* b = buf.data();
  const char* const e = r.ptr;
  if (buf[0] == '-' && std::all_of(b + 1, e, [](char c) { return c == '0' || c == '.'; })) ++b;
  out.append(b, e);
}

}  // namespace roprec
