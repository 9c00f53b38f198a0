/// \file palette.cpp
/// Colours, verdict styles and ticks of the reports (see palette.hpp).
#include "plugin/report/palette.hpp"

#include <algorithm>
#include <cmath>

namespace roprec::report {
namespace {

struct Rgb {
  double r, g, b;
};

/// viridis at t ∈ [0, 1] (matplotlib `_viridis_data` sampled at 0, 0.1, …, 1).
Rgb viridis(double t) {
  static constexpr std::array<std::array<int, 3>, 11> kV{{{68, 1, 84},
                                                          {72, 36, 117},
                                                          {65, 68, 135},
                                                          {53, 95, 141},
                                                          {42, 120, 142},
                                                          {33, 145, 140},
                                                          {34, 168, 132},
                                                          {68, 191, 112},
                                                          {122, 209, 81},
                                                          {189, 223, 38},
                                                          {253, 231, 37}}};
  if (!std::isfinite(t)) t = 0;
  t = std::clamp(t, 0.0, 1.0) * 10.0;
  const int i = std::min(9, static_cast<int>(std::floor(t)));
  const double f = t - i;
  return {kV[i][0] + f * (kV[i + 1][0] - kV[i][0]), kV[i][1] + f * (kV[i + 1][1] - kV[i][1]),
          kV[i][2] + f * (kV[i + 1][2] - kV[i][2])};
}

std::string hex(const Rgb& c) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string s = "#";
  for (const double x : {c.r, c.g, c.b}) {
    const int v = std::clamp(static_cast<int>(std::lround(x)), 0, 255);
    s += kHex[v >> 4];
    s += kHex[v & 15];
  }
  return s;
}

}  // namespace

std::string viridisHex(double t) { return hex(viridis(t)); }

const std::array<VerdictStyle, 6> kVerdicts{{
    {Verdict::kConforms, "conforms", "ok", "conforms", "#2da44e"},
    {Verdict::kConformsAfterCompensation, "conforms after compensation", "comp", "after comp.",
     "#d4a72c"},
    {Verdict::kNotCapable, "not capable", "nc", "not capable", "#cf222e"},
    {Verdict::kUnreachable, "unreachable", "unr", "unreachable", "#57606a"},
    {Verdict::kSingular, "singular", "sing", "singular", "#8250df"},
    {Verdict::kNotConverged, "not converged", "nconv", "not converged", "#bc4c00"},
}};

const VerdictStyle& styleOf(Verdict v) {
  const auto it = std::find_if(kVerdicts.begin(), kVerdicts.end(),
                               [v](const VerdictStyle& s) { return s.verdict == v; });
  return it != kVerdicts.end() ? *it : kVerdicts[0];
}

double niceStep(double raw) {
  if (!(raw > 0) || !std::isfinite(raw)) return 1.0;
  const double e = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / e;
  const double m = f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0;
  return m * e;
}

int decimalsFor(double step) {
  if (!(step > 0)) return 0;
  return std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 6);
}

std::vector<double> ticksIn(double lo, double hi, double step) {
  std::vector<double> t;
  const double eps = 1e-6 * step;
  for (double k = std::ceil((lo - eps) / step); k * step <= hi + eps && t.size() < 64; k += 1.0) {
    t.push_back(k * step);
  }
  return t;
}

}  // namespace roprec::report
