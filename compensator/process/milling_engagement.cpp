#include "compensator/process/milling_engagement.hpp"

#include <algorithm>
#include <cmath>

namespace roprec {
namespace {

constexpr double kEngagedDepth = 1e-6;  // material thinner than this is not cut [m]
/// The margin of the cells' cover and reach tests, per metre of coordinate magnitude (and 1 m):
/// segmentDistance and the cells' bounds are rounded by a few ε S ≈ 1e-15 S.
constexpr double kCoverMargin = 1e-12;

double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double L2 = ab.squaredNorm();
  const double t = L2 > 0 ? std::clamp((p - a).dot(ab) / L2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

std::int64_t cellIndex(double v, double size) {
  return static_cast<std::int64_t>(std::floor(v / size));
}

}  // namespace

EngagementTracker::EngagementTracker(const StockShape& stock, double diameter, int lateral_samples)
    : stock_(stock),
      R_(0.5 * diameter),
      R_in_(R_ * (1 - 1e-9)),
      cell_(0.25 * diameter),
      base_top_(stock.box_min && stock.box_max ? std::min(stock.top_z, stock.box_max->z())
                                               : stock.top_z),
      samples_(std::max(2, lateral_samples)) {}

double EngagementTracker::topAt(const Eigen::Vector2d& p) const {
  if (stock_.box_min && stock_.box_max &&
      (p.x() < stock_.box_min->x() || p.x() > stock_.box_max->x() || p.y() < stock_.box_min->y() ||
       p.y() > stock_.box_max->y())) {
    return -1e300;
  }
  double top = base_top_;
  const auto it = grid_.find({cellIndex(p.x(), cell_), cellIndex(p.y(), cell_)});
  if (it == grid_.end()) return top;
  // the floor: some recorded move holding p is that low (a min of the same doubles as over every
  // move, so the order does not matter)
  top = std::min(top, it->second.floor);
  for (const std::uint32_t i : it->second.moves) {
    const Move& m = moves_[i];
    if (m.z < top && segmentDistance(p, m.a, m.b) < R_in_) top = m.z;
  }
  return top;
}

bool EngagementTracker::engaged(const Eigen::Vector2d& b, double bz, const Eigen::Vector2d& f,
                                const Eigen::Vector2d& l, double s, double& depth) const {
  const Eigen::Vector2d p = b + s * l + std::sqrt(std::max(0.0, R_ * R_ - s * s)) * f;
  depth = topAt(p) - bz;
  return depth > kEngagedDepth;
}

double EngagementTracker::boundary(const Eigen::Vector2d& b, double bz, const Eigen::Vector2d& f,
                                   const Eigen::Vector2d& l, double s_in, double s_out) const {
  double depth = 0;
  while (std::abs(s_out - s_in) > kBoundaryResolution) {
    const double mid = 0.5 * (s_in + s_out);
    (engaged(b, bz, f, l, mid, depth) ? s_in : s_out) = mid;
  }
  return 0.5 * (s_in + s_out);
}

MillingEngagement EngagementTracker::engagementAt(const Vec3& a, const Vec3& b) const {
  MillingEngagement e;
  const Eigen::Vector2d b2 = b.head<2>();
  const Eigen::Vector2d d = b2 - a.head<2>();
  if (!(d.norm() > 0)) return e;
  const Eigen::Vector2d f = d / d.norm();
  const Eigen::Vector2d l(-f.y(), f.x());
  const double step = 2 * R_ / samples_;
  const auto offset = [&](int k) { return -R_ + (k + 0.5) * step; };
  bool prev = false;
  double lo = -R_;
  for (int k = 0; k < samples_; ++k) {
    double depth = 0;
    const bool in = engaged(b2, b.z(), f, l, offset(k), depth);
    if (in) e.ap = std::max(e.ap, depth);
    if (in && !prev) lo = k == 0 ? -R_ : boundary(b2, b.z(), f, l, offset(k), offset(k - 1));
    if (!in && prev) e.ae += boundary(b2, b.z(), f, l, offset(k - 1), offset(k)) - lo;
    prev = in;
  }
  if (prev) e.ae += R_ - lo;
  if (!(e.ae > 0)) e = MillingEngagement{};
  return e;
}

void EngagementTracker::record(const Vec3& a, const Vec3& b) {
  const Eigen::Vector2d a2 = a.head<2>();
  const Eigen::Vector2d b2 = b.head<2>();
  if (!((b2 - a2).norm() > 0)) return;
  const double z = std::min(a.z(), b.z());
  if (!(z < base_top_)) return;  // lowers no top (topAt starts at or below base_top_)
  const std::uint32_t id = allocate({a2, b2, z, 0});
  // every grid cell its capsule's bounding box touches (each point the capsule holds is in one)
  const Eigen::Vector2d lo = a2.cwiseMin(b2).array() - R_;
  const Eigen::Vector2d hi = a2.cwiseMax(b2).array() + R_;
  for (std::int64_t ix = cellIndex(lo.x(), cell_); ix <= cellIndex(hi.x(), cell_); ++ix)
    for (std::int64_t iy = cellIndex(lo.y(), cell_); iy <= cellIndex(hi.y(), cell_); ++iy)
      listIn(ix, iy, id);
  if (moves_[id].cells == 0) free_.push_back(id);
}

std::uint32_t EngagementTracker::allocate(const Move& m) {
  if (free_.empty()) {
    moves_.push_back(m);
    return static_cast<std::uint32_t>(moves_.size() - 1);
  }
  const std::uint32_t id = free_.back();
  free_.pop_back();
  moves_[id] = m;
  return id;
}

EngagementTracker::Region EngagementTracker::region(std::int64_t ix, std::int64_t iy,
                                                    const Move& m) const {
  // the points p with floor(p / cell) = i lie in [i cell, (i + 1) cell] up to the rounding of the
  // division and of the products (a few ε S): the margin is far wider
  const double x0 = static_cast<double>(ix) * cell_;
  const double y0 = static_cast<double>(iy) * cell_;
  const double S =
      std::max({std::abs(x0), std::abs(y0), m.a.cwiseAbs().maxCoeff(), m.b.cwiseAbs().maxCoeff()}) +
      2 * R_;
  const double e = kCoverMargin * (1 + S);
  return {x0 - e, y0 - e, x0 + cell_ + e, y0 + cell_ + e, e};
}

bool EngagementTracker::outsideStock(const Region& r) const {
  // topAt returns before the grid at every point outside the box
  return stock_.box_min && stock_.box_max &&
         (r.x1 < stock_.box_min->x() || r.x0 > stock_.box_max->x() || r.y1 < stock_.box_min->y() ||
          r.y0 > stock_.box_max->y());
}

bool EngagementTracker::reaches(const Move& m, const Region& r) const {
  // |p − c| ≤ the half diagonal for every p of the region: dist(p) ≥ dist(c) − half diagonal
  const Eigen::Vector2d c(0.5 * (r.x0 + r.x1), 0.5 * (r.y0 + r.y1));
  const double half_diagonal = 0.5 * std::hypot(r.x1 - r.x0, r.y1 - r.y0) + r.margin;
  return segmentDistance(c, m.a, m.b) - half_diagonal <= R_ + r.margin;
}

bool EngagementTracker::covers(const Move& m, const Region& r) const {
  // the region's points topAt reads the grid for: those in the (closed) box, exactly
  double x0 = r.x0, y0 = r.y0, x1 = r.x1, y1 = r.y1;
  if (stock_.box_min && stock_.box_max) {
    x0 = std::max(x0, stock_.box_min->x());
    y0 = std::max(y0, stock_.box_min->y());
    x1 = std::min(x1, stock_.box_max->x());
    y1 = std::min(y1, stock_.box_max->y());
  }
  // the capsule {dist < R_in} is convex: its corners inside (by the margin) hold the rectangle
  const double inside = R_in_ - r.margin;
  return segmentDistance({x0, y0}, m.a, m.b) < inside &&
         segmentDistance({x1, y0}, m.a, m.b) < inside &&
         segmentDistance({x0, y1}, m.a, m.b) < inside &&
         segmentDistance({x1, y1}, m.a, m.b) < inside;
}

template <class Drop>
void EngagementTracker::unlist(Cell& c, Drop drop) {
  std::erase_if(c.moves, [&](const std::uint32_t i) {
    if (!drop(moves_[i])) return false;
    if (--moves_[i].cells == 0) free_.push_back(i);
    return true;
  });
  if (c.moves.empty()) c.moves.shrink_to_fit();
}

void EngagementTracker::listIn(std::int64_t ix, std::int64_t iy, std::uint32_t id) {
  const Move m = moves_[id];
  const Region r = region(ix, iy, m);
  if (outsideStock(r) || !reaches(m, r)) return;
  Cell& c = grid_[{ix, iy}];
  if (!(m.z < c.floor)) return;  // the cell is nowhere above the floor
  if (covers(m, r)) {
    c.floor = m.z;
    unlist(c, [&](const Move& o) { return !(o.z < m.z); });
    return;
  }
  const auto same = [&](const Move& o) { return o.a == m.a && o.b == m.b; };
  for (const std::uint32_t i : c.moves)
    if (!(m.z < moves_[i].z) && same(moves_[i])) return;  // already there as low or lower
  unlist(c, [&](const Move& o) { return !(o.z < m.z) && same(o); });
  c.moves.push_back(id);
  ++moves_[id].cells;
}

MillingEngagement EngagementTracker::cut(const Vec3& a, const Vec3& b) {
  const MillingEngagement e = engagementAt(a, b);
  record(a, b);
  return e;
}

}  // namespace roprec
