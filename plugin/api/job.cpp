#include "plugin/api/job.hpp"

#include <algorithm>
#include <cmath>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"

namespace roprec::api {

const char* version() { return ROPREC_VERSION_STRING; }

int PredictionResult::failed() const {
  return static_cast<int>(std::count_if(holes.begin(), holes.end(), [](const HolePrediction& h) {
    return h.status != HoleStatus::kOk;
  }));
}

namespace {

PredictionContext loadContext(const std::string& cell_path, const std::string& program_path,
                              const JobOptions& o, bool load_holes = true) {
  PredictionContext c = loadPredictionContext(cell_path, program_path, o.holes, o.uncertainty,
                                              o.match_tol_mm, load_holes);
  if (o.fanuc_turn_axes) {
    c.model.config_options.fanuc_turn_axes = *o.fanuc_turn_axes;
    if (c.job.program) c.job.program->fanuc_turn_axes = *o.fanuc_turn_axes;
  }
  return c;
}

double perpNorm(const Vec3& v, const Vec3& a) { return (v - v.dot(a) * a).norm(); }

// ---- compensation stages after compensateHoles

/// Every target of a drill cycle moves with its drill point: T_new = ΔT · T · Rz(ψ).
std::vector<std::string> editProgram(CompensationResult& r) {
  std::vector<std::string> refused;
  postproc::Program& prog = *r.context.job.program;
  prog.position_min_decimals = 5;  // 0.01 µm: the written target carries the compensation
  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HoleCompensation& h = r.holes[i];
    if (!h.ok) continue;
    const HoleSource& src = r.context.job.sources[i];
    for (const int t : src.targets) {
      const postproc::Target& tg = prog.targets()[static_cast<size_t>(t)];
      const Pose T_W_t = src.T_W_frame * postproc::targetPose(prog, tg);
      const Pose T_W_new = h.delta * T_W_t * Pose(Eigen::AngleAxisd(h.psi, Vec3::UnitZ()));
      std::optional<postproc::Configuration> cfg;
      if (tg.config.present()) cfg = postproc::parseConfigurationText(h.config_text);
      const postproc::EditResult er =
          postproc::replaceTargetPose(prog, t, src.T_W_frame.inverse() * T_W_new, cfg);
      if (!er.ok) {
        refused.push_back("hole " + h.id + " target " +
                          (tg.name.empty() ? std::to_string(t) : tg.name) + ": " + er.reason);
      }
    }
  }
  return refused;
}

bool wristJump(const Vec6& a, const Vec6& b, double threshold) {
  return std::abs(a[3] - b[3]) > threshold || std::abs(a[5] - b[5]) > threshold;
}

/// Before/after statistics: errors ⊥ axis, conforming holes, axis-4/6 jumps within a face.
CompensationResult::Stats compensationStats(const CompensationResult& r, double jump_threshold) {
  CompensationResult::Stats s;
  const auto& req = r.context.job.requests;
  const HoleCompensation* prev = nullptr;
  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HoleCompensation& h = r.holes[i];
    if (h.before.status == HoleStatus::kOk)
      s.error_before_um.push_back(h.before.position_error * 1e6);
    if (h.before.verdict == Verdict::kConforms) ++s.conform_before;
    if (h.ok) {
      s.residual_after_um.push_back(perpNorm(h.residual, h.T_nominal.linear().col(2)) * 1e6);
      if (h.after.verdict == Verdict::kConforms) ++s.conform_after;
    }
    const bool same_face = i > 0 && req[i].T_W_tcp.linear().col(2).dot(
                                        req[i - 1].T_W_tcp.linear().col(2)) > std::cos(10.0 * kDeg);
    if (prev && h.ok && prev->ok && same_face) {
      s.jumps_after += wristJump(h.theta_cmd, prev->theta_cmd, jump_threshold) ? 1 : 0;
      s.jumps_before += wristJump(h.before.joints, prev->before.joints, jump_threshold) ? 1 : 0;
    }
    prev = &h;
  }
  return s;
}

}  // namespace

PredictionResult predictJob(const std::string& cell_path, const std::string& program_path,
                            const JobOptions& options, const ProgressFn& progress) {
  PredictionResult r;
  r.context = loadContext(cell_path, program_path, options);
  const auto& req = r.context.job.requests;
  PredictionData data(r.context.model);
  r.holes.reserve(req.size());
  std::optional<Vec6> prev;
  for (size_t i = 0; i < req.size(); ++i) {
    r.holes.push_back(predictHole(r.context.model, data, req[i], prev ? &*prev : nullptr));
    if (r.holes.back().status == HoleStatus::kOk) prev = r.holes.back().joints;
    if (progress) progress(i + 1, req.size());
  }
  r.summary = summarize(r.holes);
  return r;
}

CompensationResult compensateJob(const std::string& cell_path, const std::string& program_path,
                                 const CompensationJob& job, const ProgressFn& progress) {
  CompensationResult r;
  r.context = loadContext(cell_path, program_path, job.job);
  if (!r.context.job.program) throw InputError(program_path, 0, "not a program roprec can rewrite");
  r.orientation = orientationModeName(job.options.mode);
  r.holes = compensateHoles(r.context.model, r.context.job.requests, job.options, &r.stats);
  if (progress) progress(r.holes.size(), r.holes.size());
  r.failed = static_cast<int>(
      std::count_if(r.holes.begin(), r.holes.end(), [](const auto& h) { return !h.ok; }));
  r.refused = editProgram(r);
  r.summary = compensationStats(r, job.options.jump_threshold);
  r.writable = true;
  if (r.failed && !job.allow_partial) {
    r.writable = false;
    r.why_not_writable =
        std::to_string(r.failed) + " of " + std::to_string(r.holes.size()) +
        " holes could not be compensated; nothing written (use --allow-partial to keep their "
        "original targets)";
  } else if (!r.refused.empty() && !job.allow_partial) {
    r.writable = false;
    r.why_not_writable =
        "the writer refused " + std::to_string(r.refused.size()) + " target edits; nothing written";
  }
  return r;
}

bool cellIsMilling(const std::string& cell_path) {
  const CellSpec cell = loadCell(cell_path);
  return cell.has_process && cell.process.str("type") == "milling";
}

MillingCompensationResult compensateMillingJob(const std::string& cell_path,
                                               const std::string& program_path) {
  MillingCompensationResult r;
  r.context = loadContext(cell_path, program_path, {}, false);
  postproc::Program& prog = *r.context.job.program;
  prog.position_min_decimals = 5;
  std::vector<Pose> frame;  // T_W_frame per point
  std::vector<MillingPathPoint> path;
  std::vector<bool> seen(prog.targets().size(), false);
  for (const postproc::Motion& mo : prog.motions) {
    if (mo.type != postproc::MotionType::kLinear || mo.target < 0 || !mo.derivation.empty())
      continue;
    const postproc::Target& t = prog.targets()[static_cast<size_t>(mo.target)];
    if (t.kind != postproc::TargetKind::kCartesian || !postproc::targetComplete(t) ||
        seen[static_cast<size_t>(mo.target)]) {
      continue;
    }
    seen[static_cast<size_t>(mo.target)] = true;
    const postproc::Frame* base =
        mo.base >= 0 ? &prog.frames[static_cast<size_t>(mo.base)] : nullptr;
    const Pose T_W_frame = base && base->resolved ? base->pose : r.context.cell.T_base_wobj;
    r.targets.push_back(mo.target);
    frame.push_back(T_W_frame);
    r.points.push_back(T_W_frame * postproc::targetPose(prog, t));
    path.push_back({r.points.back(), mo.speed_mm_s >= 0 ? mo.speed_mm_s * 1e-3 : -1.0});
  }
  if (r.points.empty()) {
    throw InputError(program_path, 0,
                     "no linear path points (LIN/MoveL/L to Cartesian targets) in the program");
  }
  r.cutting = decideCutting(r.context.model.process.milling, r.context.cell.T_base_wobj, path);
  r.points_comp = compensateMillingPath(r.context.model, r.points, &r.cutting);
  for (size_t i = 0; i < r.points_comp.size(); ++i) {
    const postproc::Target& t = prog.targets()[static_cast<size_t>(r.targets[i])];
    const PathPointCompensation& p = r.points_comp[i];
    if (!p.ok) {
      r.failures.push_back("path point " + std::to_string(i + 1) + " (" +
                           prog.files[static_cast<size_t>(t.file)].path + ":" +
                           std::to_string(t.line) + "): not compensated: " + p.reason);
      continue;
    }
    std::optional<postproc::Configuration> cfg;
    if (t.config.present()) cfg = postproc::parseConfigurationText(p.config_text);
    const postproc::EditResult er =
        postproc::replaceTargetPose(prog, r.targets[i], frame[i].inverse() * p.T_programmed, cfg);
    if (!er.ok) r.refused.push_back("path point " + std::to_string(i + 1) + ": " + er.reason);
  }
  return r;
}

std::vector<std::string> writeCompensatedProgram(
    PredictionContext& context, const std::string& program_out,
    const std::vector<std::pair<std::string, std::string>>& extra) {
  if (!context.job.program)
    throw InputError(context.job.path, 0, "not a program roprec can rewrite");
  postproc::writeProgram(*context.job.program, program_out);
  std::vector<std::string> written = postproc::outputPaths(*context.job.program, program_out);
  for (const auto& [path, text] : extra) {
    writeFileAtomic(path, text);
    written.push_back(path);
  }
  return written;
}

}  // namespace roprec::api
