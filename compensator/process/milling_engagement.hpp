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
/// Earlier moves are kept in a uniform grid of cells D/4 × D/4; a query at p visits p's cell only,
/// where top(p) = min(stock top, floor, z of every listed move whose capsule holds p). The cells
/// hold only what can still set a top there, so the memory is bounded by the cells of the stock
/// area swept, not by the moves recorded (a move listed in no cell is freed, its slot reused):
/// - floor: the lowest z of a move whose capsule holds the whole cell (the capsule is convex: its
///   four corners); every point of the cell is at most that high, so no move at z' ≥ floor is
///   listed there, now or later;
/// - a move whose XY segment is that of a listed move at z' ≤ z (the same doubles, so the same
///   distances) is not listed, and it replaces a listed one at z' ≥ z;
/// - a cell outside the box (topAt never reads it) or out of the capsule's reach lists nothing,
///   and a move not below the stock's top is not kept at all.
/// Each rule drops a move only where another kept one (or the floor) already gives a top ≤ its z,
/// so topAt is exactly (bit for bit: a min of the same doubles) that of the plain list of every
/// move; the tests check it against such a list. The tests of cover and reach use the distances
/// with a margin of 1e-12 (1 + S) m for coordinates of magnitude S, above 10⁴ times their rounding.
/// What remains listed is at the edge of the area swept: a cell the boundary of the capsules
/// crosses keeps each move whose capsule reaches into it unless one of the rules drops it, so a
/// path repeated exactly holds a bounded number of moves, while passes whose edges differ (a
/// real path's µm deviations) add their edge moves there (the interior stays bounded).

#include <cstddef>
#include <cstdint>
#include <limits>
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
  /// The moves held (listed in at least one cell) and the cells: what the tracker's memory grows
  /// with.
  [[nodiscard]] std::size_t movesHeld() const { return moves_.size() - free_.size(); }
  [[nodiscard]] std::size_t cellsHeld() const { return grid_.size(); }

 private:
  struct Move {
    Eigen::Vector2d a, b;
    double z;
    std::uint32_t cells;  ///< the cells listing it (0: a free slot)
  };
  struct Cell {
    double floor{std::numeric_limits<double>::infinity()};
    std::vector<std::uint32_t> moves;
  };
  struct CellKey {
    std::int64_t ix, iy;
    bool operator==(const CellKey&) const = default;
  };
  struct CellHash {
    std::size_t operator()(const CellKey& k) const {
      return static_cast<std::size_t>(k.ix * 73856093LL ^ k.iy * 19349663LL);
    }
  };
  /// The points a cell's index maps to, widened by the margin.
  struct Region {
    double x0, y0, x1, y1, margin;
  };
  [[nodiscard]] double topAt(const Eigen::Vector2d& p) const;
  /// Whether the leading circle's point at lateral offset s of the move ending at b (feed f, left
  /// normal l) is in material deeper than 1 µm; its depth into `depth`.
  [[nodiscard]] bool engaged(const Eigen::Vector2d& b, double bz, const Eigen::Vector2d& f,
                             const Eigen::Vector2d& l, double s, double& depth) const;
  /// The offset between s_in (engaged) and s_out (not) where the engagement ends.
  [[nodiscard]] double boundary(const Eigen::Vector2d& b, double bz, const Eigen::Vector2d& f,
                                const Eigen::Vector2d& l, double s_in, double s_out) const;
  [[nodiscard]] Region region(std::int64_t ix, std::int64_t iy, const Move& m) const;
  [[nodiscard]] bool outsideStock(const Region& r) const;
  /// Whether the move's capsule can hold a point of the region / holds all of it.
  [[nodiscard]] bool reaches(const Move& m, const Region& r) const;
  [[nodiscard]] bool covers(const Move& m, const Region& r) const;
  /// Lists move `id` in the cell (ix, iy) unless the cell's rules drop it there.
  void listIn(std::int64_t ix, std::int64_t iy, std::uint32_t id);
  /// Unlists the cell's moves `drop` selects; a move listed nowhere any more is freed.
  template <class Drop>
  void unlist(Cell& c, Drop drop);
  std::uint32_t allocate(const Move& m);
  StockShape stock_;
  double R_;
  double R_in_;  ///< a capsule holds p when dist(p, segment) < R_in_ = R (1 − 1e-9)
  double cell_;  ///< the cells' side D/4
  double base_top_;
  int samples_;
  std::vector<Move> moves_;
  std::vector<std::uint32_t> free_;
  std::unordered_map<CellKey, Cell, CellHash> grid_;
};

}  // namespace roprec
