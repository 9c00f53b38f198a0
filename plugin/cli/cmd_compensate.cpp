/// `roprec compensate`: pre-offset the drill targets so the predicted real holes land on the
/// nominal ones; optionally choose the rotation about each drill axis; write the corrected
/// program in its own dialect (only the compensated targets' bytes change), the corrected-target
/// export and the report.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/compensation/compensation.hpp"
#include "compensator/support/error.hpp"
#include "compensator/compensation/milling_compensation.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/json.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "plugin/api/report.hpp"

namespace roprec::cli {
namespace {

Json poseJsonContract(const Pose& T) {
  Json j = Json::object();
  j.set("position_mm", Json::vector(T.translation() * 1e3, 6));
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
  return j;
}

double perpNorm(const Vec3& v, const Vec3& a) { return (v - v.dot(a) * a).norm(); }

std::string csvField(double v, int decimals) { return formatNumber(v, decimals); }

/// Milling: every linear path point of the program is compensated with the coupled force
/// iteration (compensator/compensation/milling_compensation.hpp).
int runMillingPath(CommandContext& ctx, const std::string& cell, const std::string& program, const std::string& out,
                   const std::optional<std::string>& targets) {
  PredictionContext c = loadPredictionContext(cell, program, std::nullopt, "", 0.5, false);
  postproc::Program& prog = *c.job.program;
  prog.position_min_decimals = 5;
  std::vector<int> idx;      // targets, path order (first use)
  std::vector<Pose> frame;   // T_W_frame per point
  std::vector<Pose> points;  // nominal TCP, base frame
  std::vector<bool> seen(prog.targets().size(), false);
  for (const postproc::Motion& mo : prog.motions) {
    if (mo.type != postproc::MotionType::kLinear || mo.target < 0 || !mo.derivation.empty()) continue;
    const postproc::Target& t = prog.targets()[static_cast<size_t>(mo.target)];
    if (t.kind != postproc::TargetKind::kCartesian || !postproc::targetComplete(t) || seen[static_cast<size_t>(mo.target)]) continue;
    seen[static_cast<size_t>(mo.target)] = true;
    const postproc::Frame* base = mo.base >= 0 ? &prog.frames[static_cast<size_t>(mo.base)] : nullptr;
    const Pose T_W_frame = base && base->resolved ? base->pose : c.cell.T_base_wobj;
    idx.push_back(mo.target);
    frame.push_back(T_W_frame);
    points.push_back(T_W_frame * postproc::targetPose(prog, t));
  }
  if (points.empty()) throw InputError(program, 0, "no linear path points (LIN/MoveL/L to Cartesian targets) in the program");
  const std::vector<PathPointCompensation> comp = compensateMillingPath(c.model, points);
  int failed = 0;
  for (size_t i = 0; i < comp.size(); ++i) {
    if (comp[i].ok) continue;
    ++failed;
    const postproc::Target& t = prog.targets()[static_cast<size_t>(idx[i])];
    ctx.err << "roprec: path point " << i + 1 << " (" << prog.files[static_cast<size_t>(t.file)].path << ":" << t.line
            << "): not compensated: " << comp[i].reason << "\n";
  }
  if (failed) {
    ctx.err << "roprec: " << failed << " of " << comp.size() << " path points could not be compensated; nothing written\n";
    return 1;
  }
  std::vector<std::string> refused;
  for (size_t i = 0; i < comp.size(); ++i) {
    const postproc::Target& t = prog.targets()[static_cast<size_t>(idx[i])];
    std::optional<postproc::Configuration> cfg;
    if (t.config.present()) cfg = postproc::parseConfigurationText(comp[i].config_text);
    const postproc::EditResult er =
        postproc::replaceTargetPose(prog, idx[i], frame[i].inverse() * comp[i].T_programmed, cfg);
    if (!er.ok) refused.push_back("path point " + std::to_string(i + 1) + ": " + er.reason);
  }
  if (!refused.empty()) {
    for (const auto& r : refused) ctx.err << "roprec: " << r << "\n";
    ctx.err << "roprec: the writer refused " << refused.size() << " target edits; nothing written\n";
    return 1;
  }
  std::string export_text;
  if (targets) {
    Json root = Json::object();
    root.set("robot", Json::str(c.robot.card.name));
    root.set("cell", Json::str(c.cell.name));
    root.set("program", Json::str(std::filesystem::path(program).filename().string()));
    root.set("process", Json::str(c.process_description));
    Json ps = Json::array();
    for (size_t i = 0; i < comp.size(); ++i) {
      const PathPointCompensation& p = comp[i];
      Json j = Json::object();
      j.set("point", Json::integer(static_cast<std::int64_t>(i + 1)));
      j.set("target", Json::str(prog.targets()[static_cast<size_t>(idx[i])].name));
      j.set("nominal", poseJsonContract(points[i]));
      Json b = Json::object();
      b.set("deviation_um", Json::vector(p.deviation_before * 1e6, 3));
      j.set("before", b);
      Json pr = poseJsonContract(p.T_programmed);
      pr.set("joints_deg", Json::vector(p.theta_cmd / kDeg, 6));
      pr.set("config", Json::str(p.config_text));
      j.set("programmed", pr);
      j.set("residual_um", Json::number(p.residual.norm() * 1e6, 4));
      j.set("force_N", Json::vector(p.force, 3));
      Json cp = Json::object();
      cp.set("converged", Json::boolean(p.coupling_converged));
      cp.set("iterations", Json::integer(p.coupling_iterations));
      cp.set("force_fixed_point_iterations", Json::integer(p.force_iterations));
      j.set("coupling", cp);
      ps.push(j);
    }
    root.set("points", ps);
    export_text = root.dump();
  }
  postproc::writeProgram(prog, out);
  if (targets) writeFileAtomic(*targets, export_text);
  if (!ctx.quiet) {
    double before = 0;
    double after = 0;
    for (const auto& p : comp) {
      before = std::max(before, p.deviation_before.norm());
      after = std::max(after, p.residual.norm());
    }
    ctx.out << "roprec compensate (milling path): " << comp.size() << " path points compensated\n";
    ctx.out << "  deviation before (coupled force) max " << formatNumber(before * 1e6, 3) << " µm; predicted residual max "
            << formatNumber(after * 1e6, 4) << " µm\n";
    for (const auto& pth : postproc::outputPaths(prog, out)) ctx.out << "  wrote " << pth << "\n";
    if (targets) ctx.out << "  wrote " << *targets << "\n";
  }
  return 0;
}

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  const auto out = args.option("o");
  const auto orientation = args.option("orientation");
  const auto targets = args.option("targets");
  const auto report = args.option("report");
  const auto holes_csv = args.option("holes");
  const auto wrist = args.option("wrist-margin");
  const auto jump = args.option("jump-threshold");
  const auto grid = args.option("grid");
  const auto turn_axes = args.option("turn-axes");
  const bool allow_partial = args.flag("allow-partial");
  const bool allow_branch = args.flag("allow-branch-change");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (!out) throw UsageError("give -o OUT (the corrected program)");
  if (pos.size() != 1) throw UsageError("give exactly one PROGRAM file");
  CompensationOptions opt;
  const std::string mode = orientation.value_or("keep");
  if (mode == "keep") {
    opt.mode = OrientationMode::kKeep;
  } else if (mode == "flip-free") {
    opt.mode = OrientationMode::kFlipFree;
  } else if (mode == "stiffest") {
    opt.mode = OrientationMode::kStiffest;
  } else {
    throw UsageError("--orientation must be keep, flip-free or stiffest");
  }
  if (wrist) opt.wrist_margin = parseNumberList(*wrist, 1, "--wrist-margin (deg)")[0] * kDeg;
  if (jump) opt.jump_threshold = parseNumberList(*jump, 1, "--jump-threshold (deg)")[0] * kDeg;
  if (grid) {
    const double g = parseNumberList(*grid, 1, "--grid")[0];
    if (g < 4 || g > 720) throw UsageError("--grid must lie in [4, 720]");
    opt.grid = static_cast<int>(g);
  }
  if (!(opt.wrist_margin >= 0) || !(opt.jump_threshold > 0)) throw UsageError("--wrist-margin >= 0, --jump-threshold > 0");
  opt.allow_branch_change = allow_branch;

  {
    const CellSpec peek = loadCell(*cell);
    if (peek.has_process && peek.process.str("type") == "milling") return runMillingPath(ctx, *cell, pos[0], *out, targets);
  }
  PredictionContext c = loadPredictionContext(*cell, pos[0], holes_csv, "");
  if (turn_axes) {
    const Eigen::VectorXd ax = parseNumberList(*turn_axes, 3, "--turn-axes (three joint numbers)");
    std::array<int, 3> a{};
    for (int i = 0; i < 3; ++i) {
      if (ax[i] < 1 || ax[i] > 6 || ax[i] != std::floor(ax[i])) throw UsageError("--turn-axes: joint numbers 1..6");
      a[static_cast<size_t>(i)] = static_cast<int>(ax[i]);
    }
    c.model.config_options.fanuc_turn_axes = a;
    if (c.job.program) c.job.program->fanuc_turn_axes = a;
  }
  if (!c.job.program) throw InputError(pos[0], 0, "not a program roprec can rewrite");
  CompensationStats stats;
  const std::vector<HoleCompensation> comp = compensateHoles(c.model, c.job.requests, opt, &stats);

  // failures
  int failed = 0;
  for (size_t i = 0; i < comp.size(); ++i) {
    if (comp[i].ok) continue;
    ++failed;
    const HoleRequest& r = c.job.requests[i];
    ctx.err << "roprec: hole " << comp[i].id;
    if (r.line > 0) ctx.err << " (" << pos[0] << ":" << r.line << ")";
    ctx.err << ": not compensated: " << comp[i].reason << "\n";
  }
  if (failed && !allow_partial) {
    ctx.err << "roprec: " << failed << " of " << comp.size()
            << " holes could not be compensated; nothing written (use --allow-partial to keep their original targets)\n";
    return 1;
  }

  // program edit: every target of a cycle moves with its drill point
  postproc::Program& prog = *c.job.program;
  prog.position_min_decimals = 5;  // 0.01 µm: the written target carries the compensation
  std::vector<std::string> refused;
  for (size_t i = 0; i < comp.size(); ++i) {
    const HoleCompensation& h = comp[i];
    if (!h.ok) continue;
    const HoleSource& src = c.job.sources[i];
    for (const int t : src.targets) {
      const postproc::Target& tg = prog.targets()[static_cast<size_t>(t)];
      const Pose T_W_t = src.T_W_frame * postproc::targetPose(prog, tg);
      const Pose T_W_new = h.delta * T_W_t * Pose(Eigen::AngleAxisd(h.psi, Vec3::UnitZ()));
      const Pose T_frame_new = src.T_W_frame.inverse() * T_W_new;
      std::optional<postproc::Configuration> cfg;
      if (tg.config.present()) cfg = postproc::parseConfigurationText(h.config_text);
      const postproc::EditResult er = postproc::replaceTargetPose(prog, t, T_frame_new, cfg);
      if (!er.ok) refused.push_back("hole " + h.id + " target " + (tg.name.empty() ? std::to_string(t) : tg.name) + ": " + er.reason);
    }
  }
  if (!refused.empty()) {
    for (const auto& r : refused) ctx.err << "roprec: " << r << "\n";
    if (!allow_partial) {
      ctx.err << "roprec: the writer refused " << refused.size() << " target edits; nothing written\n";
      return 1;
    }
  }

  // export
  std::string export_text;
  if (targets) {
    const bool csv = targets->size() > 4 && targets->substr(targets->size() - 4) == ".csv";
    if (csv) {
      std::ostringstream s;
      s << "id,status,nominal_x_mm,nominal_y_mm,nominal_z_mm,nominal_qw,nominal_qx,nominal_qy,nominal_qz,"
           "before_dx_um,before_dy_um,before_dz_um,before_rx_urad,before_ry_urad,before_rz_urad,"
           "programmed_x_mm,programmed_y_mm,programmed_z_mm,programmed_qw,programmed_qx,programmed_qy,programmed_qz,"
           "j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg,config,rotation_about_axis_deg,residual_um,U_robot_um,U_mach_um,"
           "U_work_um,k,verdict,reason\n";
      for (const HoleCompensation& h : comp) {
        const Pose& N = h.ok ? h.T_nominal : c.job.requests[static_cast<size_t>(&h - comp.data())].T_W_tcp;
        const Pose& P = h.ok ? h.T_programmed : N;
        const Eigen::Quaterniond qn = quaternionFromRotation(N.linear());
        const Eigen::Quaterniond qp = quaternionFromRotation(P.linear());
        s << h.id << "," << (h.ok ? "compensated" : "original-kept");
        for (int k = 0; k < 3; ++k) s << "," << csvField(N.translation()[k] * 1e3, 6);
        s << "," << csvField(qn.w(), 9) << "," << csvField(qn.x(), 9) << "," << csvField(qn.y(), 9) << "," << csvField(qn.z(), 9);
        for (int k = 0; k < 3; ++k) s << "," << csvField(h.before.d_work[k] * 1e6, 3);
        for (int k = 0; k < 3; ++k) s << "," << csvField(h.before.d_rot[k] * 1e6, 3);
        for (int k = 0; k < 3; ++k) s << "," << csvField(P.translation()[k] * 1e3, 6);
        s << "," << csvField(qp.w(), 9) << "," << csvField(qp.x(), 9) << "," << csvField(qp.y(), 9) << "," << csvField(qp.z(), 9);
        for (int k = 0; k < 6; ++k) s << "," << csvField((h.ok ? h.theta_cmd[k] : h.before.joints[k]) / kDeg, 6);
        s << ",\"" << (h.ok ? h.config_text : h.before.config) << "\"," << csvField(h.psi / kDeg, 4);
        const Vec3 a = N.linear().col(2);
        s << "," << csvField(h.ok ? perpNorm(h.residual, a) * 1e6 : h.before.position_error * 1e6, 4);
        const HolePrediction& u = h.ok ? h.after : h.before;
        s << "," << csvField(u.U_robot * 1e6, 3) << "," << csvField(u.U_mach * 1e6, 3) << "," << csvField(u.U_work * 1e6, 3)
          << "," << csvField(u.k, 4) << "," << verdictName(u.verdict) << ",\"" << h.reason << "\"\n";
      }
      export_text = s.str();
    } else {
      Json root = Json::object();
      root.set("robot", Json::str(c.robot.card.name));
      root.set("cell", Json::str(c.cell.name));
      root.set("program", Json::str(std::filesystem::path(pos[0]).filename().string()));
      root.set("orientation", Json::str(orientationModeName(opt.mode)));
      Json hs = Json::array();
      for (size_t i = 0; i < comp.size(); ++i) {
        const HoleCompensation& h = comp[i];
        Json j = Json::object();
        j.set("id", Json::str(h.id));
        j.set("status", Json::str(h.ok ? "compensated" : "original-kept"));
        if (!h.ok) j.set("reason", Json::str(h.reason));
        const Pose& N = h.ok ? h.T_nominal : c.job.requests[i].T_W_tcp;
        j.set("nominal", poseJsonContract(N));
        Json b = Json::object();
        Json dev = Json::object();
        dev.set("translation", Json::vector(h.before.d_work * 1e6, 3));
        dev.set("rotation_urad", Json::vector(h.before.d_rot * 1e6, 3));
        b.set("deviation_um", dev);
        b.set("verdict", Json::str(verdictName(h.before.verdict)));
        j.set("before", b);
        if (h.ok) {
          Json p = poseJsonContract(h.T_programmed);
          p.set("joints_deg", Json::vector(h.theta_cmd / kDeg, 6));
          p.set("config", Json::str(h.config_text));
          j.set("programmed", p);
          j.set("rotation_about_axis_deg", Json::number(h.psi / kDeg, 4));
          const Vec3 a = N.linear().col(2);
          j.set("residual_um", Json::number(perpNorm(h.residual, a) * 1e6, 4));
          j.set("residual_vector_um", Json::vector(h.residual * 1e6, 4));
          j.set("branch_changed", Json::boolean(h.branch_changed));
          if (!h.note.empty()) j.set("note", Json::str(h.note));
        }
        const HolePrediction& u = h.ok ? h.after : h.before;
        Json un = Json::object();
        un.set("U_robot", Json::number(u.U_robot * 1e6, 3));
        un.set("U_mach", Json::number(u.U_mach * 1e6, 3));
        un.set("U_work", Json::number(u.U_work * 1e6, 3));
        un.set("k", Json::number(u.k, 4));
        j.set("uncertainty_um", un);
        j.set("verdict", Json::str(verdictName(u.verdict)));
        hs.push(j);
      }
      root.set("holes", hs);
      export_text = root.dump();
    }
  }

  // report
  std::string report_text;
  std::vector<HolePrediction> after_preds;
  if (report) {
    ReportInput in;
    in.title = "roprec compensation — " + std::filesystem::path(pos[0]).filename().string() + " (" +
               orientationModeName(opt.mode) + ")";
    in.robot = c.robot.card.name;
    in.cell = c.cell.name + " (" + c.cell.file + ")";
    in.program = pos[0];
    in.process = c.process_description;
    in.uncertainty_method = uncertaintyMethodText(c.model.uncertainty);
    in.uncertainty_source = c.model.uncertainty.source;
    in.default_tolerance_mm = c.cell.tolerance_mm;
    in.compensation = true;
    after_preds.reserve(comp.size());
    for (size_t i = 0; i < comp.size(); ++i) after_preds.push_back(comp[i].ok ? comp[i].after : comp[i].before);
    in.summary = summarize(after_preds);
    for (size_t i = 0; i < comp.size(); ++i) {
      ReportHole rh;
      rh.prediction = &comp[i].before;
      rh.T_W_tcp = c.job.requests[i].T_W_tcp;
      if (comp[i].ok) {
        rh.residual_um = perpNorm(comp[i].residual, comp[i].T_nominal.linear().col(2)) * 1e6;
        rh.T_W_programmed = comp[i].T_programmed;
        rh.rotation_about_axis_deg = comp[i].psi / kDeg;
        rh.after = &comp[i].after;
      }
      in.holes.push_back(rh);
    }
    report_text = renderReport(in);
  }

  // outputs (atomic each)
  postproc::writeProgram(prog, *out);
  if (targets) writeFileAtomic(*targets, export_text);
  if (report) writeFileAtomic(*report, report_text);

  // statistics
  std::vector<double> before;
  std::vector<double> after;
  int conform_before = 0;
  int conform_after = 0;
  int flips_before = 0;
  int flips_after = 0;
  const HoleCompensation* prevb = nullptr;
  for (const HoleCompensation& h : comp) {
    if (h.before.status == HoleStatus::kOk) before.push_back(h.before.position_error * 1e6);
    if (h.before.verdict == Verdict::kConforms) ++conform_before;
    if (h.ok) {
      after.push_back(perpNorm(h.residual, h.T_nominal.linear().col(2)) * 1e6);
      if (h.after.verdict == Verdict::kConforms) ++conform_after;
    }
    const size_t idx = static_cast<size_t>(&h - comp.data());
    const bool same_face = idx > 0 && c.job.requests[idx].T_W_tcp.linear().col(2).dot(
                                          c.job.requests[idx - 1].T_W_tcp.linear().col(2)) > std::cos(10.0 * kDeg);
    if (prevb && h.ok && prevb->ok && same_face) {
      if (std::abs(h.theta_cmd[3] - prevb->theta_cmd[3]) > opt.jump_threshold ||
          std::abs(h.theta_cmd[5] - prevb->theta_cmd[5]) > opt.jump_threshold) {
        ++flips_after;
      }
      if (std::abs(h.before.joints[3] - prevb->before.joints[3]) > opt.jump_threshold ||
          std::abs(h.before.joints[5] - prevb->before.joints[5]) > opt.jump_threshold) {
        ++flips_before;
      }
    }
    prevb = &h;
  }
  auto stat = [](std::vector<double> v) {
    if (v.empty()) return std::string("n/a");
    std::sort(v.begin(), v.end());
    double mean = 0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    char buf[128];
    std::snprintf(buf, sizeof buf, "mean %.3f, max %.3f", mean, v.back());
    return std::string(buf);
  };
  if (!ctx.quiet) {
    ctx.out << "roprec compensate (" << orientationModeName(opt.mode) << "): " << comp.size() << " holes, "
            << (comp.size() - static_cast<size_t>(failed)) << " compensated\n";
    ctx.out << "  position error ⊥ axis before [µm]: " << stat(before) << "\n";
    ctx.out << "  predicted residual after    [µm]: " << stat(after) << "\n";
    ctx.out << "  holes conforming (ISO 14253-1): before " << conform_before << ", after " << conform_after << "\n";
    ctx.out << "  axis-4/6 jumps > " << formatNumber(opt.jump_threshold / kDeg, 0) << " deg between holes of a face: before "
            << flips_before << ", after " << flips_after << "\n";
    if (stats.relaxed_jumps) ctx.out << "  note: no orientation sequence met the jump threshold; it was relaxed\n";
    if (stats.relaxed_wrist > 0) {
      ctx.out << "  note: at " << stats.relaxed_wrist << " holes no rotation about the drill axis meets |θ5| ≥ "
              << formatNumber(opt.wrist_margin / kDeg, 0) << "° (flagged in the export)\n";
    }
    for (const auto& p : postproc::outputPaths(prog, *out)) ctx.out << "  wrote " << p << "\n";
    if (targets) ctx.out << "  wrote " << *targets << "\n";
    if (report) ctx.out << "  wrote " << *report << "\n";
  }
  return failed ? 1 : 0;
}

const CommandRegistration reg{
    {"compensate", "pre-offset drill targets; corrected program, target export and report",
     "usage: roprec compensate --cell CELL.xml PROGRAM -o OUT [--orientation keep|flip-free|stiffest]\n"
     "                         [--targets F.csv|F.json] [--report F.html] [--holes HOLES.csv]\n"
     "                         [--allow-partial] [--allow-branch-change] [--wrist-margin DEG]\n"
     "                         [--jump-threshold DEG] [--grid N] [--turn-axes \"1 4 6\"]\n\n"
     "For every hole: the motor-side command θ_m = θ_d + K⁻¹τ(θ_d) (+ servo term) that makes the\n"
     "predicted real TCP land on the nominal hole, and the programmed target = the controller's\n"
     "rigid FK of θ_m with its configuration flags. Every target of a drill cycle moves with it.\n"
     "--orientation: keep (positions only), flip-free (rotation about the drill axis chosen for the\n"
     "whole program by dynamic programming + NLopt: no axis-4/6 jump > --jump-threshold (60°),\n"
     "|θ5| ≥ --wrist-margin (10°), same IK branch unless --allow-branch-change), stiffest (least\n"
     "predicted U_work under the same constraints).\n"
     "OUT is written in the program's dialect; only the compensated targets' bytes change.\n"
     "FANUC: turn digits 1 and 2 are changed only when $SCR_GRP[1].$TURN_AXIS is known (--turn-axes or\n"
     "the cell's <controller fanuc_turn_axes>); otherwise such edits are refused.\n"
     "With a milling cell every linear path point is compensated instead, with the coupled force\n"
     "iteration (the force depends on the deviation); the export lists points, forces and iterations.\n"
     "Unreachable, singular or non-converging holes are listed; without --allow-partial nothing is\n"
     "written and the exit code is 1; with it they keep their original targets and are flagged.\n",
     50, run}};

}  // namespace
}  // namespace roprec::cli
