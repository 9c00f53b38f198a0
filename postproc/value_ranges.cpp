#include "postproc/value_ranges.hpp"

#include <cmath>
#include <string>

#include "compensator/support/error.hpp"

namespace roprec::postproc {

namespace {

constexpr double kMaxPositionMm = 1e5;
constexpr double kMaxEulerDeg = 720.0;
constexpr double kMaxJoint = 1e5;
constexpr double kRapidUnusedAxis = 9e9;
constexpr double kMaxConfiguration = 1000.0;
constexpr double kMaxSpeedMmS = 10000.0;  // 10 m/s: beyond every industrial arm's TCP speed

/// Where a number was written: its own token when it has one, else the target's line.
std::pair<std::string, int> whereOf(const Program& p, const Target& t, const NumberField& f) {
  const int file = f.present() ? f.file : t.file;
  if (file < 0 || file >= static_cast<int>(p.files.size())) {
    return {p.files.empty() ? std::string() : p.files.front().path, t.line};
  }
  const SourceFile& sf = p.files[static_cast<std::size_t>(file)];
  return {sf.path, f.present() ? sf.lineOf(f.offset) : t.line};
}

std::string targetName(const Target& t) {
  return t.name.empty() ? std::string("inline target") : "target " + t.name;
}

void refuse(const Program& p, const Target& t, const NumberField& f, const std::string& what,
            const char* range) {
  const auto [file, line] = whereOf(p, t, f);
  throw InputError(file, line,
                   targetName(t) + ": " + what + " = " + numberText(f.value) +
                       " is out of range (" + range +
                       "); a corrupted or mistyped number would move the robot by that much");
}

/// `what(k)` names the value; it is only built for the message.
template <class What>
void checkBound(const Program& p, const Target& t, const NumberField& f, const What& what,
                double bound, const char* range) {
  if (!f.known()) return;
  if (!(std::fabs(f.value) <= bound)) refuse(p, t, f, what(), range);
}

const char* eulerName(Orientation o, std::size_t k) {
  static const char* const kKuka[] = {"A", "B", "C"};
  static const char* const kFanuc[] = {"W", "P", "R"};
  static const char* const kXyz[] = {"rx", "ry", "rz"};
  if (o == Orientation::kKukaAbc) return kKuka[k];
  if (o == Orientation::kFanucWpr) return kFanuc[k];
  return kXyz[k];
}

void checkOrientation(const Program& p, const Target& t) {
  if (t.orientation == Orientation::kKukaAbc || t.orientation == Orientation::kFanucWpr ||
      t.orientation == Orientation::kXyzIntrinsic) {
    for (std::size_t k = 0; k < 3; ++k) {
      checkBound(
          p, t, t.rot[k], [&] { return std::string("angle ") + eulerName(t.orientation, k); },
          kMaxEulerDeg, "|angle| <= 720 deg");
    }
    return;
  }
  if (t.orientation != Orientation::kQuaternion) return;
  double n2 = 0;
  for (const NumberField& f : t.rot) {
    if (!f.known()) return;
    n2 += f.value * f.value;
  }
  const double n = std::sqrt(n2);
  if (n >= 0.9 && n <= 1.1) return;
  const auto [file, line] = whereOf(p, t, t.rot[0]);
  throw InputError(file, line,
                   targetName(t) + ": the quaternion [" + numberText(t.rot[0].value) + "," +
                       numberText(t.rot[1].value) + "," + numberText(t.rot[2].value) + "," +
                       numberText(t.rot[3].value) + "] has norm " + numberText(n) +
                       ", not 1 (accepted 0.9..1.1); the controller refuses a quaternion that is "
                       "not normalised");
}

void checkTarget(const Program& p, const Target& t) {
  static const char* const kXyz[] = {"x", "y", "z"};
  if (t.kind == TargetKind::kCartesian) {
    for (std::size_t k = 0; k < 3; ++k) {
      checkBound(
          p, t, t.pos[k], [&] { return std::string("position ") + kXyz[k] + " (mm)"; },
          kMaxPositionMm, "|x| <= 100000 mm");
    }
    checkOrientation(p, t);
  } else {
    for (std::size_t k = 0; k < 6; ++k) {
      checkBound(
          p, t, t.joints[k], [&] { return "joint " + std::to_string(k + 1); }, kMaxJoint,
          "|q| <= 100000 deg or mm");
    }
  }
  for (std::size_t k = 0; k < 6; ++k) {
    const NumberField& e = t.ext[k];
    if (!e.known() || e.value == kRapidUnusedAxis) continue;
    checkBound(
        p, t, e, [&] { return "external axis " + std::to_string(k + 1); }, kMaxJoint,
        "|e| <= 100000 deg or mm, or 9E+09 for an axis not used");
  }
  for (std::size_t k = 0; k < 4; ++k) {
    checkBound(
        p, t, t.cf_fields[k], [&] { return "configuration number " + std::to_string(k + 1); },
        kMaxConfiguration, "|cf| <= 1000");
  }
}

void checkFrame(const Program& p, const Frame& f) {
  if (!f.resolved) return;
  const double d_mm = f.pose.translation().norm() * 1e3;
  if (d_mm <= kMaxPositionMm && f.pose.matrix().allFinite()) return;
  const std::string file = f.file >= 0 && f.file < static_cast<int>(p.files.size())
                               ? p.files[static_cast<std::size_t>(f.file)].path
                               : (p.files.empty() ? std::string() : p.files.front().path);
  throw InputError(file, f.line,
                   "frame " + f.ref + " is " + numberText(d_mm) +
                       " mm from its origin; out of range (<= 100000 mm): a corrupted or "
                       "mistyped number");
}

void checkMotion(const Program& p, const Motion& m) {
  const std::string file = m.file >= 0 && m.file < static_cast<int>(p.files.size())
                               ? p.files[static_cast<std::size_t>(m.file)].path
                               : (p.files.empty() ? std::string() : p.files.front().path);
  // a known linear speed (speed_mm_s < 0: not stated or not known) drives the hole recognition's
  // feed and the machining times
  if (m.speed_mm_s == 0) {
    throw InputError(file, m.line,
                     p.text(m.instruction) +
                         ": speed 0 mm/s: the motion would not move; hint: give the speed the "
                         "motion runs at (> 0 mm/s)");
  }
  if (m.speed_mm_s >= 0 && !(m.speed_mm_s <= kMaxSpeedMmS)) {
    throw InputError(file, m.line,
                     p.text(m.instruction) + ": speed " + numberText(m.speed_mm_s) +
                         " mm/s is out of range (<= 10000 mm/s; set by the motion's speed or "
                         "the program's speed variable): a corrupted or mistyped number");
  }
  if (!m.has_offset) return;
  const double d_mm = m.offset.get().translation().norm() * 1e3;
  if (d_mm <= kMaxPositionMm && m.offset.get().matrix().allFinite()) return;
  throw InputError(file, m.line,
                   p.text(m.instruction) + ": offset of " + numberText(d_mm) +
                       " mm is out of range (<= 100000 mm): a corrupted or mistyped number");
}

}  // namespace

void checkValueRanges(const Program& p, RangeErrors& first) {
  const auto keep = [](std::exception_ptr& e, const auto& check) {
    if (e) return;
    try {
      check();
    } catch (const InputError&) {
      e = std::current_exception();
    }
  };
  keep(first.target, [&] {
    for (const Target& t : p.target_list)
      if (!t.uses.empty()) checkTarget(p, t);
  });
  keep(first.frame, [&] {
    for (const Frame& f : p.frames) checkFrame(p, f);
  });
  keep(first.motion, [&] {
    for (const Motion& m : p.motions) checkMotion(p, m);
  });
}

void RangeErrors::rethrow() const {
  for (const std::exception_ptr& e : {target, frame, motion})
    if (e) std::rethrow_exception(e);
}

void checkValueRanges(const Program& p) {
  // only the targets a motion moves to: an unused placeholder point (`Xp9={X 666666.688,…}` in a
  // .dat) places nothing
  for (const Target& t : p.target_list)
    if (!t.uses.empty()) checkTarget(p, t);
  for (const Frame& f : p.frames) checkFrame(p, f);
  for (const Motion& m : p.motions) checkMotion(p, m);
}

}  // namespace roprec::postproc
