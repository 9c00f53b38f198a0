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

}  // namespace roprec
