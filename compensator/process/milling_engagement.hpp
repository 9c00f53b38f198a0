#pragma once
/// \file milling_engagement.hpp
/// The engagement (ae, ap) of a peripheral end mill at each path point, from the stock and the
/// program's own earlier passes (docs/process.md §4.5), instead of the cell's constants.
///
/// Geometry (workobject frame, the tool axis along its z; 2½-D: the material at a point of the
/// XY plane is the column between the floor and its top):
/// - Stock: a box [min, max] (its top face z = max.z), or a plane (XY unbounded).
/// - A cutting move from tip a to tip b (tool tips, the tool's radius R) removes, over the capsule
///   {p : dist(p, [a, b]_XY) < R}, everything above min(a.z, b.z): the material top there becomes
///   min(top, min(a.z, b.z)).
/// - At the end b of a move with feed direction f = (b − a)_XY/|…| and left normal l = e_z × f,
///   the leading half of the tool's circle is sampled at K lateral offsets
///   s_k = −R + (k + ½) D/K:   p_k = b + s_k l + √(R² − s_k²) f;
///   the material there is engaged when top(p_k) − b.z > 1 µm (top from the stock and every
///   earlier move, the current one excluded). Then
///     ae = (number of engaged samples) · D/K   (the width cut across the feed; D for a slot),
///     ap = max_k (top(p_k) − b.z)               (the depth of the deepest engaged column).
///   ae is exact to D/K for a straight wall (the engaged samples form one run); ap is exact when
///   the material top is flat over the leading half.
/// Earlier moves are kept in a uniform grid of cells D × D (each move listed in every cell its
/// capsule's bounding box touches): a query visits one cell, so a path costs O(n) with O(n) memory
/// for the moves.

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "compensator/support/rotation.hpp"

namespace roprec {

struct StockShape {
  double top_z{0};                       ///< [m], workobject frame
  std::optional<Vec3> box_min, box_max;  ///< a box stock (top_z = box_max.z); none: a plane
};

struct MillingEngagement {
  double ae{0};  ///< [m]
  double ap{0};  ///< [m]
  [[nodiscard]] bool cuts() const { return ae > 0 && ap > 0; }
};

class EngagementTracker {
 public:
  EngagementTracker(const StockShape& stock, double diameter, int lateral_samples = 200);
  /// The engagement at the end of the cutting move a → b (tool tips, workobject frame [m]); then
  /// records the move as removed material. A move without XY length engages nothing (and is not
  /// recorded).
  MillingEngagement cut(const Vec3& a, const Vec3& b);

 private:
  struct Move {
    Eigen::Vector2d a, b;
    double z;
  };
  [[nodiscard]] double topAt(const Eigen::Vector2d& p) const;
  [[nodiscard]] std::int64_t cellKey(std::int64_t ix, std::int64_t iy) const;
  StockShape stock_;
  double R_;
  int samples_;
  std::vector<Move> moves_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
};

}  // namespace roprec
