#pragma once
/// \file fixed_chars.hpp
/// Fixed-point number text, fast: the bytes of std::to_chars(first, last, v, fixed, decimals).
///
/// std::to_chars with a precision prints the exact binary value rounded to `decimals` places
/// (round half to even on an exact tie), at ~40 ns a number. Most numbers roprec writes (joint
/// angles, positions, µm) scale to r = |v| · 10^d below 2^52. There r = fl(|v| · 10^d) is one
/// rounding (10^d is exact for d ≤ 22), and floor(r) + 1/2 is a double: rounding is monotone,
/// so the exact |v| · 10^d lies on the same side of floor(r) + 1/2 as r, unless r is on it.
/// Then |v| · 10^d and r round to the same integer m, and the text is m's digits with a point
/// before the last d. Everything else (r exactly on a half, r ≥ 2^52, d > 17, non-finite
/// values) is std::to_chars itself, so the bytes are always std::to_chars' bytes (checked
/// against it in tests/fixed_chars_test.cpp).

#include <charconv>
#include <string>

namespace roprec {

/// std::to_chars(first, last, v, std::chars_format::fixed, decimals), the same result and
/// bytes (decimals ≥ 0); never throws.
std::to_chars_result toFixedChars(char* first, char* last, double v, int decimals);

/// Appends v with `decimals` places (clamped to 0 … 60) to `out`: toFixedChars' text, except
/// that a value that rounds to zero has no sign ("-0.000" is written "0.000"); non-finite values
/// as std::to_chars writes them ("nan", "inf", "-inf"): callers that must never write them
/// check first.
void appendFixed(std::string& out, double v, int decimals);

}  // namespace roprec
