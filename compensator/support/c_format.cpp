#include "compensator/support/c_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "compensator/support/fixed_chars.hpp"

namespace roprec {

namespace {
std::string nonFinite(double v) {
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}
}  // namespace

std::string cFixed(double v, int decimals) {
  if (!std::isfinite(v)) return nonFinite(v);
  char buf[400];  // DBL_MAX with 60 places fits
  const auto r = toFixedChars(buf, buf + sizeof buf, v, std::clamp(decimals, 0, 60));
  if (r.ec != std::errc()) return cGeneral(v, 17);
  return std::string(buf, r.ptr);
}

std::string cGeneral(double v, int precision) {
  if (!std::isfinite(v)) return nonFinite(v);
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general,
                               std::clamp(precision, 1, 17));
  return std::string(buf, r.ptr);
}

std::string formatCardNumber(double v, int significant) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific,
                                 std::max(0, significant - 1));
  std::string s(buf, res.ptr);  // e.g. 2.413e+06
  const std::size_t e = s.find('e');
  std::string mant = s.substr(0, e);
  if (mant.find('.') != std::string::npos) {  // 8.380 -> 8.38, 2.000 -> 2
    while (mant.back() == '0') mant.pop_back();
    if (mant.back() == '.') mant.pop_back();
  }
  std::string exp = s.substr(e + 1);
  const bool neg = exp.front() == '-';
  exp.erase(0, exp.find_first_not_of("+-"));
  exp.erase(0, std::min(exp.find_first_not_of('0'), exp.size() - 1));
  return exp == "0" ? mant : mant + "e" + (neg ? "-" : "") + exp;
}

}  // namespace roprec
