#pragma once
/// \file palette.hpp
/// What every report draws with: the colour map (viridis, matplotlib's perceptually uniform
/// sequential map, van der Walt & Smith 2015: 11 anchors interpolated linearly in sRGB), the
/// verdict styles (label, CSS class, badge, colour) and axis ticks at "nice" steps.

#include <array>
#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"

namespace roprec::report {

/// viridis at t ∈ [0, 1] (clamped; NaN → 0) as "#rrggbb".
std::string viridisHex(double t);

struct VerdictStyle {
  Verdict verdict;
  const char* label;  ///< human-readable
  const char* cls;    ///< CSS class suffix
  const char* badge;  ///< short badge text (the table; the full key is its tooltip)
  const char* bar;    ///< bar / cross colour
};

/// Every verdict, in the reports' order (conforms first).
extern const std::array<VerdictStyle, 6> kVerdicts;
const VerdictStyle& styleOf(Verdict v);

/// 1, 2 or 5 × 10^k nearest above `raw` (1 for a non-positive or non-finite raw).
double niceStep(double raw);
/// The decimals that show a tick step (0 … 6).
int decimalsFor(double step);
/// Multiples of `step` within [lo, hi] (inclusive, with a small tolerance; at most 64).
std::vector<double> ticksIn(double lo, double hi, double step);

}  // namespace roprec::report
