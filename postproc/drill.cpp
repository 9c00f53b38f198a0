#include "postproc/drill.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

bool sameFrameIdx(const Program& p, int a, int b) {
  if (a == b) return true;
  if (a < 0 || b < 0) return false;
  const Frame& fa = p.frames[static_cast<std::size_t>(a)];
  const Frame& fb = p.frames[static_cast<std::size_t>(b)];
  return iequals(fa.ref, fb.ref) && fa.resolved == fb.resolved &&
         fa.pose.matrix() == fb.pose.matrix();
}

bool drillMarker(const std::string& m) {
  const std::string u = upper(m);
  return u.rfind("DWELL", 0) == 0 || u.find("SPINDLE") != std::string::npos ||
         u.find("DRILL") != std::string::npos || u.find("PLUNGE") != std::string::npos ||
         u.find("BOOR") != std::string::npos || u.find("BOHR") != std::string::npos;
}

}  // namespace

std::vector<Hole> recognizeHoles(const Program& p, const RecognitionOptions& o) {
  std::vector<Hole> holes;
  const std::size_t M = p.motions.size();
  const double line_tol = o.line_tol_mm * 1e-3;
  const double ori_tol = o.ori_tol_deg * kDeg;
  const Vec3 tool_axis = o.tool_axis.normalized();
  std::vector<bool> used(p.target_list.size(), false);
  std::size_t i = 0;
  while (i < M) {
    const Motion& m0 = p.motions[i];
    const std::optional<Pose> T0 = motionPose(p, m0);
    if (!T0) {
      ++i;
      continue;
    }
    const Vec3 a = T0->linear() * tool_axis;
    const Vec3 p0 = T0->translation();
    std::size_t j = i + 1;
    for (; j < M; ++j) {
      const Motion& mj = p.motions[j];
      if (mj.type != MotionType::kLinear) break;
      const std::optional<Pose> Tj = motionPose(p, mj);
      if (!Tj) break;
      if (!sameFrameIdx(p, mj.base, m0.base) || !sameFrameIdx(p, mj.tool, m0.tool)) break;
      if (smallRotationDifference(Tj->linear(), T0->linear()).norm() > ori_tol) break;
      if ((Tj->translation() - p0).cross(a).norm() > line_tol) break;
    }
    if (j - i >= 2) {
      std::size_t bottom = i;
      double dmax = 0;
      double vmax = 0;
      for (std::size_t k = i; k < j; ++k) {
        const double d = (motionPose(p, p.motions[k])->translation() - p0).dot(a);
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
        const double prev = (motionPose(p, p.motions[k - 1])->translation() - p0).dot(a);
        const double cur = (motionPose(p, p.motions[k])->translation() - p0).dot(a);
        const double v = p.motions[k].speed_mm_s;
        if (cur > prev + line_tol && v > 0 && v < vmax) {
          slower = true;
          feed = std::min(feed, v);
        }
      }
      if (slower) {  // the first move into the material at the feed starts at the surface
        for (std::size_t k = i + 1; k < j; ++k) {
          const double prev = (motionPose(p, p.motions[k - 1])->translation() - p0).dot(a);
          const double cur = (motionPose(p, p.motions[k])->translation() - p0).dot(a);
          const double v = p.motions[k].speed_mm_s;
          if (cur > prev + line_tol && v > 0 && v <= feed * (1 + 1e-9)) {
            surface = k - 1;
            surface_d = prev;
            break;
          }
        }
      }
      if (slower) h.evidence.push_back("feed slower than approach/retract");
      bool marker = false;
      for (std::size_t k = (i > 0 ? i - 1 : i); k < j; ++k) {
        for (const std::string& mk : p.motions[k].markers) {
          if (drillMarker(mk)) {
            marker = true;
            h.evidence.push_back(mk);
          }
        }
      }
      if (p.motions[bottom].fine) h.evidence.push_back("exact stop at the bottom");
      if (dmax > line_tol && (slower || marker)) {
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
        h.position = motionPose(p, p.motions[bottom])->translation();
        h.axis = a;
        if (slower && surface_d < dmax - line_tol) {
          h.surface = motionPose(p, p.motions[surface])->translation();
          h.surface_motion = static_cast<int>(surface);
          h.depth = dmax - surface_d;
        } else {
          // no feed change: the program does not say where the material starts
          h.surface = p0;
          h.depth = 0.0;
          h.evidence.push_back("no feed change: surface and depth not known from the program");
        }
        h.base = m0.base;
        h.tool = m0.tool;
        h.id = "H" + std::to_string(holes.size() + 1);
        holes.push_back(std::move(h));
        i = j;
        continue;
      }
    }
    // a drilling macro call right after a single target
    bool call = false;
    for (const std::string& mk : m0.markers) {
      const std::string u = upper(mk);
      if (u.rfind("CALL", 0) == 0 && u.find("DRILL") != std::string::npos) call = true;
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
      h.evidence = m0.markers;
      h.id = "H" + std::to_string(holes.size() + 1);
      used[static_cast<std::size_t>(m0.target)] = true;
      holes.push_back(std::move(h));
    }
    ++i;
  }
  return holes;
}

std::vector<HoleMatch> matchHoles(const std::vector<Hole>& holes, const Program& p,
                                  const std::vector<HoleSpec>& specs, double tol_mm) {
  std::vector<HoleMatch> out;
  std::set<int> taken;
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const Hole& hole = holes[h];
    // by id: a hole-list id equal to the name of one of the cycle's targets
    int by_id = -1;
    for (std::size_t s = 0; s < specs.size() && by_id < 0; ++s) {
      for (const int t : hole.targets) {
        if (t >= 0 && iequals(p.target_list[static_cast<std::size_t>(t)].name, specs[s].id))
          by_id = static_cast<int>(s);
      }
    }
    if (by_id >= 0 && taken.count(by_id) == 0) {
      taken.insert(by_id);
      out.push_back(HoleMatch{static_cast<int>(h), by_id, 0.0});
      continue;
    }
    const Vec3 bottom = hole.position * 1e3;
    const Vec3 entry = bottom - hole.axis * hole.depth * 1e3;
    int best = -1;
    double best_d = tol_mm;
    for (std::size_t s = 0; s < specs.size(); ++s) {
      if (taken.count(static_cast<int>(s)) != 0) continue;
      if (specs[s].direction.dot(hole.axis) < std::cos(1.0 * kDeg)) continue;
      const Vec3 q = specs[s].position_mm;
      // distance to the line through the drill axis, limited to the segment extended by depth
      const double depth = specs[s].depth_mm.value_or(0.0);
      const double tlo = -depth - 50.0;
      const double thi = hole.depth * 1e3 + depth + 50.0;
      const double t = std::clamp((q - entry).dot(hole.axis), tlo, thi);
      const double d = (entry + hole.axis * t - q).norm();
      if (d <= best_d) {
        best_d = d;
        best = static_cast<int>(s);
      }
    }
    if (best >= 0) {
      taken.insert(best);
      out.push_back(HoleMatch{static_cast<int>(h), best, best_d});
    }
  }
  return out;
}

}  // namespace roprec::postproc
