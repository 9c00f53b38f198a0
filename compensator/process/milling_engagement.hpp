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
///   earlier move, the current one excluded). Each run of engaged samples spans [lo, hi] in s:
///   its ends are refined by bisection on the engaged test between the engaged sample and its
///   neighbour to kBoundaryResolution (a run reaching the first or last sample ends at ∓R). Then
///     ae = Σ_runs (hi − lo)                       (the width cut across the feed; D for a slot),
///     ap = max_k (top(p_k) − b.z)               (the depth of the deepest engaged column).
///   The point on the circle at offset s lies at s across the feed, so ae is exact (to
///   kBoundaryResolution) for a straight wall parallel to the feed and for the chord at a straight
///   entry face; features narrower than D/K between two samples are missed. ap is exact when the
///   material top is flat over the leading half.
/// A chain of moves along the real tool path queries the engagement at the tool's position
/// (engagementAt) and records the move once it knows where the tool really went (record): the
/// next pass then cuts what this one really left (milling_compensation.hpp).
/// Earlier moves are kept in a uniform grid of cells D × D (each move listed in every cell its
/// capsule's bounding box touches): a query visits one cell, so a path costs O(n) with O(n) memory
/// for the moves.

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "compensator/support/rotation.hpp"

namespace roprec {

/// The ends of an engaged run of lateral samples are refined to this [m].
constexpr double kBoundaryResolution = 1e-9;

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
  /// The engagement at the end of the cutting move a → b (tool tips, workobject frame [m]) in the
  /// material left by the stock and the recorded moves. A move without XY length engages nothing.
  [[nodiscard]] MillingEngagement engagementAt(const Vec3& a, const Vec3& b) const;
  /// Records the move a → b as removed material (a move without XY length is not recorded).
  void record(const Vec3& a, const Vec3& b);
  /// engagementAt(a, b), then record(a, b).
  MillingEngagement cut(const Vec3& a, const Vec3& b);

 private:
  struct Move {
    Eigen::Vector2d a, b;
    double z;
  };
  [[nodiscard]] double topAt(const Eigen::Vector2d& p) const;
  /// Whether the leading circle's point at lateral offset s of the move ending at b (feed f, left
  /// normal l) is in material deeper than 1 µm; its depth into `depth`.
  [[nodiscard]] bool engaged(const Eigen::Vector2d& b, double bz, const Eigen::Vector2d& f,
                             const Eigen::Vector2d& l, double s, double& depth) const;
  /// The offset between s_in (engaged) and s_out (not) where the engagement ends.
  [[nodiscard]] double boundary(const Eigen::Vector2d& b, double bz, const Eigen::Vector2d& f,
                                const Eigen::Vector2d& l, double s_in, double s_out) const;
  [[nodiscard]] std::int64_t cellKey(std::int64_t ix, std::int64_t iy) const;
  StockShape stock_;
  double R_;
  int samples_;
  std::vector<Move> moves_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
};

}  // namespace roprec
