#include "postproc/drill.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>

#include "compensator/support/error.hpp"
#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

/// The motion goes to a Cartesian target with a component roprec could not evaluate.
bool statesUnknownValues(const Program& p, const Motion& m) {
  if (m.target < 0) return false;
  const Target& t = p.targets()[static_cast<std::size_t>(m.target)];
  if (t.kind != TargetKind::kCartesian) return false;
  const auto unknown = [](const NumberField& f) { return f.named() && !f.expr_known; };
  return std::any_of(t.pos.begin(), t.pos.end(), unknown) ||
         std::any_of(t.rot.begin(), t.rot.end(), unknown);
}

/// `s` contains `w` (upper-case ASCII), ignoring the case of `s`.
bool containsUpper(std::string_view s, std::string_view w, bool at_start) {
  const auto up = [](char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; };
  if (w.size() > s.size()) return false;
  const std::size_t last = at_start ? 0 : s.size() - w.size();
  for (std::size_t i = 0; i <= last; ++i) {
    std::size_t k = 0;
    while (k < w.size() && up(s[i + k]) == w[k]) ++k;
    if (k == w.size()) return true;
  }
  return false;
}

}  // namespace

/// Poses of the motions around the cycle being read, each computed once (motionPose builds a
/// rotation from the target's angles): a ring of the last kSize motion indices.
class HoleRecognizer::PoseCache {
 public:
  PoseCache() : slots_(kSize) {}
  const std::optional<Pose>& operator()(const Program& p, std::size_t k) {
    Slot& s = slots_[k % kSize];
    if (s.k != k) {
      s.k = k;
      s.pose = motionPose(p, p.motions[k]);
    }
    return s.pose;
  }

 private:
  static constexpr std::size_t kSize = 64;
  struct Slot {
    std::size_t k{static_cast<std::size_t>(-1)};
    std::optional<Pose> pose;
  };
  std::vector<Slot> slots_;
};

bool drillMarker(std::string_view m) {
  return containsUpper(m, "DWELL", true) || containsUpper(m, "SPINDLE", false) ||
         containsUpper(m, "DRILL", false) || containsUpper(m, "PLUNGE", false) ||
         containsUpper(m, "BOOR", false) || containsUpper(m, "BOHR", false);
}

bool processMarker(std::string_view m) {
  return drillMarker(m) && !containsUpper(m, "DWELL", true);
}

HoleRecognizer::HoleRecognizer(const RecognitionOptions& o)
    : o_(o), cache_(std::make_unique<PoseCache>()) {}
HoleRecognizer::~HoleRecognizer() = default;
HoleRecognizer::HoleRecognizer(HoleRecognizer&&) noexcept = default;

void HoleRecognizer::retired(std::size_t motions, std::size_t target_begin,
                             std::size_t target_end) {
  if (!holes_.empty() || motions > next_)
    throw InternalError("HoleRecognizer::retired: holes not taken, or motions not yet read");
  next_ -= motions;
  target_end = std::min(target_end, used_.size());
  if (target_begin < target_end) {
    used_.erase(used_.begin() + static_cast<std::ptrdiff_t>(target_begin),
                used_.begin() + static_cast<std::ptrdiff_t>(target_end));
  }
  cache_ = std::make_unique<PoseCache>();
}

std::vector<Hole> recognizeHoles(const Program& p, const RecognitionOptions& o) {
  HoleRecognizer r(o);
  r.advance(p, true);
  return r.take();
}

void HoleRecognizer::advance(const Program& p, bool final) {
  std::vector<Hole>& holes = holes_;
  const std::size_t M = p.motions.size();
  const double line_tol = o_.line_tol_mm * 1e-3;
  const double ori_tol = o_.ori_tol_deg * kDeg;
  const Vec3 tool_axis = o_.tool_axis.normalized();
  std::vector<bool>& used = used_;
  used.resize(p.target_list.size(), false);
  auto pose = [&](std::size_t k) -> const std::optional<Pose>& { return (*cache_)(p, k); };
  std::size_t& i = next_;
  while (i < M) {
    const Motion& m0 = p.motions[i];
    // a copy: the scan below reuses the cache's slots
    const std::optional<Pose> T0 = pose(i);  // NOLINT(performance-unnecessary-copy-initialization)
    if (!T0) {
      ++i;
      continue;
    }
    const Vec3 a = T0->linear() * tool_axis;
    const Vec3 p0 = T0->translation();
    std::size_t j = i + 1;
    bool cut_by_unknown = false;  // the line goes on to a point whose value roprec cannot know
    for (; j < M; ++j) {
      const Motion& mj = p.motions[j];
      if (mj.type != MotionType::kLinear) break;
      const std::optional<Pose>& Tj = pose(j);
      if (!Tj) {
        cut_by_unknown = statesUnknownValues(p, mj);
        break;
      }
      if (!sameFrame(p, mj.base, m0.base) || !sameFrame(p, mj.tool, m0.tool)) break;
      if (smallRotationDifference(Tj->linear(), T0->linear()).norm() > ori_tol) break;
      if ((Tj->translation() - p0).cross(a).norm() > line_tol) break;
    }
    // the cycle may go on past the last motion read, and the last motion's markers may still
    // grow (a marker belongs to the motion before it): wait for the motion after the cycle
    if (j >= M && !final) return;
    if (j - i >= 2) {
      std::size_t bottom = i;
      double dmax = 0;
      double vmax = 0;
      for (std::size_t k = i; k < j; ++k) {
        const double d = (pose(k)->translation() - p0).dot(a);
        if (d > dmax + 1e-12) {
          dmax = d;
          bottom = k;
        }
        vmax = std::max(vmax, p.motions[k].speed_mm_s);
      }
      Hole h;
      bool slower = false;
      std::size_t surface = i;
      double surface_d = 0;
      double feed = vmax;  // the slowest move into the material is the drilling feed
      for (std::size_t k = i + 1; k < j; ++k) {
        const double prev = (pose(k - 1)->translation() - p0).dot(a);
        const double cur = (pose(k)->translation() - p0).dot(a);
        const double v = p.motions[k].speed_mm_s;
        if (cur > prev + line_tol && v > 0 && v < vmax) {
          slower = true;
          feed = std::min(feed, v);
        }
      }
      if (slower) {  // the first move into the material at the feed starts at the surface
        for (std::size_t k = i + 1; k < j; ++k) {
          const double prev = (pose(k - 1)->translation() - p0).dot(a);
          const double cur = (pose(k)->translation() - p0).dot(a);
          const double v = p.motions[k].speed_mm_s;
          if (cur > prev + line_tol && v > 0 && v <= feed * (1 + 1e-9)) {
            surface = k - 1;
            surface_d = prev;
            break;
          }
        }
      }
      h.slower_feed = slower;
      bool marker = false;
      h.marker_begin = static_cast<int>(i > 0 ? i - 1 : i);
      h.marker_end = static_cast<int>(j);
      // a dwell alone is no evidence (a gripper waits at a placement too): a spindle or drill
      // call or a drilling comment is
      bool dwell = false;
      for (std::size_t k = (i > 0 ? i - 1 : i); k < j; ++k) {
        for (const std::string& mk : p.markers(p.motions[k])) {
          marker = marker || processMarker(mk);
          dwell = dwell || drillMarker(mk);
        }
      }
      h.dwell_only = !slower && !marker && dwell && o_.dwell_candidates;
      h.fine_bottom = p.motions[bottom].fine;
      // A cycle whose next point is stated by values roprec cannot evaluate (a RAPID component
      // set at run time) may end deeper than the points it knows: its bottom is unknown, so it
      // is not taken as a hole (the unresolved value is reported with its line).
      if (dmax > line_tol && (slower || marker || h.dwell_only) && !cut_by_unknown) {
        h.entry_motion = static_cast<int>(i);
        h.bottom_motion = static_cast<int>(bottom);
        h.entry_target = m0.target;
        h.bottom_target = p.motions[bottom].target;
        for (std::size_t k = i; k < j; ++k) {
          const int t = p.motions[k].target;
          if (std::find(h.targets.begin(), h.targets.end(), t) == h.targets.end())
            h.targets.push_back(t);
          used[static_cast<std::size_t>(t)] = true;
        }
        h.position = pose(bottom)->translation();
        h.axis = a;
        if (slower && surface_d < dmax - line_tol) {
          h.surface = pose(surface)->translation();
          h.surface_motion = static_cast<int>(surface);
          h.depth = dmax - surface_d;
        } else {
          // no feed change: the program does not say where the material starts
          h.surface = p0;
          h.depth = 0.0;
          h.no_feed_change = true;
        }
        h.base = m0.base;
        h.tool = m0.tool;
        h.id = "H" + std::to_string(++count_);
        holes.push_back(std::move(h));
        i = j;
        continue;
      }
    }
    // a drilling macro call right after a single target
    bool call = false;
    for (const std::string& mk : p.markers(m0)) {
      if (containsUpper(mk, "CALL", true) && containsUpper(mk, "DRILL", false)) call = true;
    }
    if (call && m0.target >= 0 && !used[static_cast<std::size_t>(m0.target)]) {
      Hole h;
      h.entry_motion = h.bottom_motion = static_cast<int>(i);
      h.entry_target = h.bottom_target = m0.target;
      h.targets = {m0.target};
      h.position = p0;
      h.surface = p0;
      h.axis = a;
      h.base = m0.base;
      h.tool = m0.tool;
      h.all_markers = true;
      h.marker_begin = static_cast<int>(i);
      h.marker_end = static_cast<int>(i + 1);
      h.id = "H" + std::to_string(++count_);
      used[static_cast<std::size_t>(m0.target)] = true;
      holes.push_back(std::move(h));
    }
    ++i;
  }
}

std::vector<std::string> holeEvidence(const Program& p, const Hole& h) {
  std::vector<std::string> e;
  if (h.slower_feed) e.emplace_back("feed slower than approach/retract");
  for (int k = std::max(0, h.marker_begin);
       k < h.marker_end && static_cast<std::size_t>(k) < p.motions.size(); ++k) {
    for (const std::string& mk : p.markers(p.motions[static_cast<std::size_t>(k)])) {
      if (h.all_markers || drillMarker(mk)) e.push_back(mk);
    }
  }
  if (h.dwell_only) e.emplace_back("on the hole list (a dwell alone is no drilling evidence)");
  if (h.fine_bottom) e.emplace_back("exact stop at the bottom");
  if (h.no_feed_change)
    e.emplace_back("no feed change: surface and depth not known from the program");
  return e;
}

std::string drillingEvidence(const Program& p, const Hole& h) {
  if (h.slower_feed) return "feed segment along the tool axis";
  for (int k = std::max(0, h.marker_begin);
       k < h.marker_end && static_cast<std::size_t>(k) < p.motions.size(); ++k) {
    const Motion& m = p.motions[static_cast<std::size_t>(k)];
    for (const std::string& mk : p.markers(m)) {
      if (processMarker(mk)) return mk + " after the motion at line " + std::to_string(m.line);
    }
  }
  return h.dwell_only ? "on the hole list" : "";
}

namespace {

/// Hole-list points for the position match, by direction then by position across it: the
/// directions are bucketed in cubes of edge 0.005 (every member within 0.25 deg of its bucket's
/// axis c); inside a bucket the points are projected on the plane perpendicular to c and hashed
/// in a 2-D grid. A query walks the hole's segment projected on that plane (projection never
/// lengthens a distance, so nothing within reach is missed): cost ~ buckets + points near the
/// axis, not the list's length.
class SpecIndex {
 public:
  SpecIndex(const std::vector<HoleSpec>& specs, double reach) : cell_(std::max(2.0 * reach, 2.0)) {
    for (std::size_t s = 0; s < specs.size(); ++s) {
      const Vec3& d = specs[s].direction;
      const Key k{index(d.x(), kDirCell), index(d.y(), kDirCell), index(d.z(), kDirCell)};
      auto [it, fresh] = bucket_of_.emplace(k, buckets_.size());
      if (fresh) {
        Bucket b;
        b.axis = Vec3((k.x + 0.5) * kDirCell, (k.y + 0.5) * kDirCell, (k.z + 0.5) * kDirCell);
        b.axis = b.axis.norm() > 0 ? Vec3(b.axis.normalized()) : Vec3::UnitZ();
        b.e1 = b.axis.unitOrthogonal();
        b.e2 = b.axis.cross(b.e1);
        buckets_.push_back(std::move(b));
      }
      Bucket& b = buckets_[it->second];
      const Vec3& q = specs[s].position_mm;
      b.cells[key2(q.dot(b.e1), q.dot(b.e2))].push_back(static_cast<int>(s));
    }
  }

  /// Calls f(spec) for every spec within `reach` of the segment a..b whose direction may be
  /// within `max_angle` (rad) of `axis`.
  template <class F>
  void near(const Vec3& axis, double max_angle, const Vec3& a, const Vec3& b, F&& f) const {
    const double cos_limit = std::cos(std::min(max_angle + kBucketRadius, kPi));
    for (const Bucket& bk : buckets_) {
      if (bk.axis.dot(axis) < cos_limit) continue;
      const Eigen::Vector2d pa(a.dot(bk.e1), a.dot(bk.e2));
      const Eigen::Vector2d pb(b.dot(bk.e1), b.dot(bk.e2));
      const double len = (pb - pa).norm();
      if (!std::isfinite(len)) continue;
      const int steps = static_cast<int>(std::min(1e6, std::ceil(2.0 * len / cell_)));
      visited_.clear();
      for (int i = 0; i <= steps; ++i) {
        const Eigen::Vector2d p =
            steps == 0 ? pa : Eigen::Vector2d(pa + (pb - pa) * (1.0 * i / steps));
        const Key c = key2(p.x(), p.y());
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          for (std::int64_t dy = -1; dy <= 1; ++dy) {
            const Key k{c.x + dx, c.y + dy, 0};
            if (std::find(visited_.begin(), visited_.end(), k) != visited_.end()) continue;
            visited_.push_back(k);
            const auto it = bk.cells.find(k);
            if (it == bk.cells.end()) continue;
            for (const int s : it->second) f(s);
          }
        }
      }
    }
  }

 private:
  static constexpr double kDirCell = 0.005;
  static constexpr double kBucketRadius = 0.005;  // > 0.005 * sqrt(3) / 2: member to axis, rad
  static constexpr double kPi = 3.14159265358979323846;
  struct Key {
    std::int64_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
      return static_cast<std::size_t>(u(k.x) * 73856093U ^ u(k.y) * 19349663U ^ u(k.z) * 83492791U);
    }
  };
  struct Bucket {
    Vec3 axis, e1, e2;
    std::unordered_map<Key, std::vector<int>, Hash> cells;
  };
  /// Clamped cell index: no UB for absurd or non-finite coordinates.
  static std::int64_t index(double v, double cell) {
    const double i = std::floor(v / cell);
    return static_cast<std::int64_t>(std::isfinite(i) ? std::clamp(i, -1e15, 1e15) : 0.0);
  }
  [[nodiscard]] Key key2(double u, double v) const {
    return Key{index(u, cell_), index(v, cell_), 0};
  }

  double cell_;
  std::vector<Bucket> buckets_;
  std::unordered_map<Key, std::size_t, Hash> bucket_of_;
  mutable std::vector<Key> visited_;
};

/// Distance (mm) of hole-list point `spec` from the drill segment of `hole`, extended by the
/// hole-list depth + 50 mm each way; nullopt when the axes are not parallel (1 deg).
std::optional<double> segmentDistance(const Hole& hole, const HoleSpec& spec) {
  if (spec.direction.dot(hole.axis) < std::cos(1.0 * kDeg)) return std::nullopt;
  const Vec3 bottom = hole.position * 1e3;
  const Vec3 entry = bottom - hole.axis * hole.depth * 1e3;
  const Vec3& q = spec.position_mm;
  const double depth = spec.depth_mm.value_or(0.0);
  const double t =
      std::clamp((q - entry).dot(hole.axis), -depth - 50.0, hole.depth * 1e3 + depth + 50.0);
  return (entry + hole.axis * t - q).norm();
}

}  // namespace

std::vector<HoleMatch> matchHoles(const std::vector<Hole>& holes, const Program& p,
                                  const std::vector<HoleSpec>& specs, double tol_mm) {
  // ids through a hash map, positions through SpecIndex (was O(H * S) scans)
  std::unordered_map<std::string, int> by_name;  // upper-case id -> first spec with it
  double max_depth = 0;
  for (std::size_t s = 0; s < specs.size(); ++s) {
    by_name.emplace(upper(specs[s].id), static_cast<int>(s));
    max_depth = std::max(max_depth, specs[s].depth_mm.value_or(0.0));
  }
  const SpecIndex index(specs, std::max(tol_mm, 0.0));
  std::vector<HoleMatch> out;
  std::vector<bool> taken(specs.size(), false);
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const Hole& hole = holes[h];
    // by id: a hole-list id equal to the name of one of the cycle's targets (the first in the list)
    int by_id = -1;
    for (const int t : hole.targets) {
      if (t < 0) continue;
      const auto it = by_name.find(upper(p.target_list[static_cast<std::size_t>(t)].name));
      if (it != by_name.end() && (by_id < 0 || it->second < by_id)) by_id = it->second;
    }
    if (by_id >= 0 && !taken[static_cast<std::size_t>(by_id)]) {
      taken[static_cast<std::size_t>(by_id)] = true;
      out.push_back(HoleMatch{static_cast<int>(h), by_id, 0.0});
      continue;
    }
    // by position: the nearest free point within tol (on a tie the later list row, as before)
    const Vec3 bottom = hole.position * 1e3;
    const Vec3 entry = bottom - hole.axis * hole.depth * 1e3;
    int best = -1;
    double best_d = tol_mm;
    index.near(hole.axis, 1.0 * kDeg, entry - hole.axis * (max_depth + 50.0 + tol_mm),
               bottom + hole.axis * (max_depth + 50.0 + tol_mm), [&](int s) {
                 if (taken[static_cast<std::size_t>(s)]) return;
                 const std::optional<double> d =
                     segmentDistance(hole, specs[static_cast<std::size_t>(s)]);
                 if (d && (*d < best_d || (*d == best_d && s > best))) {
                   best_d = *d;
                   best = s;
                 }
               });
    if (best >= 0) {
      taken[static_cast<std::size_t>(best)] = true;
      out.push_back(HoleMatch{static_cast<int>(h), best, best_d});
    }
  }
  return out;
}

}  // namespace roprec::postproc

namespace roprec::postproc {

std::vector<Hole> withHoleListEvidence(const Program& p, std::vector<Hole> holes,
                                       const std::vector<HoleSpec>& specs, double tol_mm,
                                       RecognitionOptions o) {
  if (specs.empty() || matchHoles(holes, p, specs, tol_mm).size() == specs.size()) return holes;
  o.dwell_candidates = true;
  std::vector<Hole> all = recognizeHoles(p, o);
  std::vector<bool> listed(all.size(), false);
  for (const HoleMatch& m : matchHoles(all, p, specs, tol_mm))
    listed[static_cast<std::size_t>(m.hole)] = true;
  std::vector<Hole> out;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].dwell_only && !listed[k]) continue;
    out.push_back(std::move(all[k]));
    out.back().id = "H" + std::to_string(out.size());
  }
  return out;
}

}  // namespace roprec::postproc
