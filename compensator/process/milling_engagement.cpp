#include "compensator/process/milling_engagement.hpp"

#include <algorithm>
#include <cmath>

namespace roprec {
namespace {

constexpr double kEngagedDepth = 1e-6;  // material thinner than this is not cut [m]

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
    : stock_(stock), R_(0.5 * diameter), samples_(std::max(2, lateral_samples)) {}

std::int64_t EngagementTracker::cellKey(std::int64_t ix, std::int64_t iy) const {
  return ix * 73856093LL ^ iy * 19349663LL;
}

double EngagementTracker::topAt(const Eigen::Vector2d& p) const {
  double top = stock_.top_z;
  if (stock_.box_min && stock_.box_max) {
    if (p.x() < stock_.box_min->x() || p.x() > stock_.box_max->x() || p.y() < stock_.box_min->y() ||
        p.y() > stock_.box_max->y()) {
      return -1e300;
    }
    top = std::min(top, stock_.box_max->z());
  }
  const double D = 2 * R_;
  const auto it = grid_.find(cellKey(cellIndex(p.x(), D), cellIndex(p.y(), D)));
  if (it == grid_.end()) return top;
  for (const std::uint32_t i : it->second) {
    const Move& m = moves_[i];
    if (m.z < top && segmentDistance(p, m.a, m.b) < R_ * (1 - 1e-9)) top = m.z;
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
  const double D = 2 * R_;
  // every grid cell its capsule's bounding box touches
  moves_.push_back({a2, b2, std::min(a.z(), b.z())});
  const auto idx = static_cast<std::uint32_t>(moves_.size() - 1);
  const Eigen::Vector2d lo = a2.cwiseMin(b2).array() - R_;
  const Eigen::Vector2d hi = a2.cwiseMax(b2).array() + R_;
  for (std::int64_t ix = cellIndex(lo.x(), D); ix <= cellIndex(hi.x(), D); ++ix)
    for (std::int64_t iy = cellIndex(lo.y(), D); iy <= cellIndex(hi.y(), D); ++iy)
      grid_[cellKey(ix, iy)].push_back(idx);
}

MillingEngagement EngagementTracker::cut(const Vec3& a, const Vec3& b) {
  const MillingEngagement e = engagementAt(a, b);
  record(a, b);
  return e;
}

}  // namespace roprec
