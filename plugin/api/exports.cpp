/// The texts a job writes: prediction JSON and report, corrected-target exports (CSV/JSON),
/// compensation report, milling path export (docs/contract.md).
#include <filesystem>
#include <sstream>

#include "plugin/api/job.hpp"
#include "plugin/api/report.hpp"

namespace roprec::api {

namespace {

std::string fileName(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

Json poseJsonContract(const Pose& T) {
  Json j = Json::object();
  j.set("position_mm", Json::vector(T.translation() * 1e3, 6));
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
  return j;
}

double perpNorm(const Vec3& v, const Vec3& a) { return (v - v.dot(a) * a).norm(); }

Json uncertaintyInputsJson(const UncertaintyInputs& in) {
  Json u = Json::object();
  u.set("method", Json::str(uncertaintyMethodText(in)));
  u.set("stiffness_rel", Json::number(in.stiffness_rel, 4));
  u.set("position_gain_rel", Json::number(in.position_gain_rel, 4));
  u.set("process_halfwidth", Json::number(in.process_halfwidth, 4));
  u.set("coverage", Json::str("2-D radial 95 % (Rayleigh), k = 2.4477"));
  u.set("source", Json::str(in.source));
  return u;
}

Json uncertaintyJson(const HolePrediction& u) {
  Json un = Json::object();
  un.set("U_robot", Json::number(u.U_robot * 1e6, 3));
  un.set("U_mach", Json::number(u.U_mach * 1e6, 3));
  un.set("U_work", Json::number(u.U_work * 1e6, 3));
  un.set("U_work_anisotropic", Json::number(u.U_work_exact * 1e6, 3));
  un.set("k", Json::number(u.k, 4));
  return un;
}

/// The report header every report shares.
ReportInput reportHeader(const PredictionContext& c, const std::string& title) {
  ReportInput in;
  in.title = title;
  in.robot = c.robot.card.name;
  in.cell = c.cell.name + " (" + c.cell.file + ")";
  in.program = c.job.path;
  in.process = c.process_description;
  for (const std::string& n : c.job.notes) {
    const std::string prefix = kResolutionPrefix;
    if (n.rfind(prefix, 0) == 0) in.resolutions.push_back(n.substr(prefix.size()));
  }
  in.uncertainty_method = uncertaintyMethodText(c.model.uncertainty);
  in.uncertainty_source = c.model.uncertainty.source;
  in.default_tolerance_mm = c.cell.tolerance_mm;
  in.generator = std::string("roprec ") + version();
  return in;
}

// ---- corrected-target export, one row / object per hole

/// The nominal pose of hole i: the chosen one when compensated, else the programmed one.
const Pose& nominalOf(const CompensationResult& r, size_t i) {
  return r.holes[i].ok ? r.holes[i].T_nominal : r.context.job.requests[i].T_W_tcp;
}

void csvQuaternion(std::ostringstream& s, const Mat3& R) {
  const Eigen::Quaterniond q = quaternionFromRotation(R);
  s << "," << formatNumber(q.w(), 9) << "," << formatNumber(q.x(), 9) << ","
    << formatNumber(q.y(), 9) << "," << formatNumber(q.z(), 9);
}

void csvRow(std::ostringstream& s, const CompensationResult& r, size_t i) {
  const HoleCompensation& h = r.holes[i];
  const Pose& N = nominalOf(r, i);
  const Pose& P = h.ok ? h.T_programmed : N;
  s << h.id << "," << (h.ok ? "compensated" : "original-kept");
  for (int k = 0; k < 3; ++k) s << "," << formatNumber(N.translation()[k] * 1e3, 6);
  csvQuaternion(s, N.linear());
  for (int k = 0; k < 3; ++k) s << "," << formatNumber(h.before.d_work[k] * 1e6, 3);
  for (int k = 0; k < 3; ++k) s << "," << formatNumber(h.before.d_rot[k] * 1e6, 3);
  for (int k = 0; k < 3; ++k) s << "," << formatNumber(P.translation()[k] * 1e3, 6);
  csvQuaternion(s, P.linear());
  for (int k = 0; k < 6; ++k)
    s << "," << formatNumber((h.ok ? h.theta_cmd[k] : h.before.joints[k]) / kDeg, 6);
  s << ",\"" << (h.ok ? h.config_text : h.before.config) << "\"," << formatNumber(h.psi / kDeg, 4);
  const Vec3 a = N.linear().col(2);
  s << "," << formatNumber(h.ok ? perpNorm(h.residual, a) * 1e6 : h.before.position_error * 1e6, 4);
  const HolePrediction& u = h.ok ? h.after : h.before;
  s << "," << formatNumber(u.U_robot * 1e6, 3) << "," << formatNumber(u.U_mach * 1e6, 3) << ","
    << formatNumber(u.U_work * 1e6, 3) << "," << formatNumber(u.k, 4) << ","
    << verdictName(u.verdict) << ",\"" << h.reason << "\"\n";
}

std::string targetsCsv(const CompensationResult& r) {
  std::ostringstream s;
  s << "id,status,nominal_x_mm,nominal_y_mm,nominal_z_mm,nominal_qw,nominal_qx,nominal_qy,nominal_"
       "qz,"
       "before_dx_um,before_dy_um,before_dz_um,before_rx_urad,before_ry_urad,before_rz_urad,"
       "programmed_x_mm,programmed_y_mm,programmed_z_mm,programmed_qw,programmed_qx,programmed_qy,"
       "programmed_qz,"
       "j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg,config,rotation_about_axis_deg,residual_um,U_"
       "robot_um,U_mach_um,"
       "U_work_um,k,verdict,reason\n";
  for (size_t i = 0; i < r.holes.size(); ++i) csvRow(s, r, i);
  return s.str();
}

/// One item whose numbers are not all finite (a bug or an input that escaped the range checks)
/// is reported as failed on its own instead of poisoning the whole output (issue 13).
Json finiteOrFailed(Json item, const std::string& id, int line) {
  if (item.finite()) return item;
  Json j = Json::object();
  j.set("id", Json::str(id));
  if (line > 0) j.set("line", Json::integer(line));
  j.set("status", Json::str("failed"));
  j.set("reason", Json::str("internal error: the result of this hole is not a finite number, so "
                            "it is not reported (please report this input)"));
  return j;
}

Json targetJson(const CompensationResult& r, size_t i) {
  const HoleCompensation& h = r.holes[i];
  Json j = Json::object();
  j.set("id", Json::str(h.id));
  j.set("status", Json::str(h.ok ? "compensated" : "original-kept"));
  if (!h.ok) j.set("reason", Json::str(h.reason));
  const Pose& N = nominalOf(r, i);
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
    j.set("residual_um", Json::number(perpNorm(h.residual, N.linear().col(2)) * 1e6, 4));
    j.set("residual_vector_um", Json::vector(h.residual * 1e6, 4));
    j.set("branch_changed", Json::boolean(h.branch_changed));
    if (!h.note.empty()) j.set("note", Json::str(h.note));
  }
  const HolePrediction& u = h.ok ? h.after : h.before;
  j.set("uncertainty_um", uncertaintyJson(u));
  j.set("verdict", Json::str(verdictName(u.verdict)));
  return j;
}

}  // namespace

Json predictionJson(const PredictionResult& r) {
  const PredictionContext& c = r.context;
  Json root = Json::object();
  root.set("robot", Json::str(c.robot.card.name));
  root.set("cell", Json::str(c.cell.name));
  root.set("program", Json::str(fileName(c.job.path)));
  root.set("process", Json::str(c.process_description));
  root.set("uncertainty_inputs", uncertaintyInputsJson(c.model.uncertainty));
  Json notes = Json::array();
  for (const auto& n : c.job.notes) notes.push(Json::str(n));
  root.set("notes", notes);
  Json hs = Json::array();
  for (size_t i = 0; i < r.holes.size(); ++i) {
    hs.push(finiteOrFailed(holeJson(r.holes[i], c.job.requests[i]), r.holes[i].id,
                           c.job.requests[i].line));
  }
  root.set("holes", hs);
  root.set("summary", summaryJson(r.summary));
  return root;
}

std::string predictionReport(const PredictionResult& r) {
  const PredictionContext& c = r.context;
  ReportInput in = reportHeader(c, "roprec prediction — " + fileName(c.job.path));
  if (!c.robot.card.model.empty())
    in.robot += " (" + vendorName(c.robot.card.vendor) + " " + c.robot.card.model + ")";
  in.summary = r.summary;
  for (size_t i = 0; i < r.holes.size(); ++i) {
    ReportHole rh;
    rh.prediction = &r.holes[i];
    rh.T_W_tcp = c.job.requests[i].T_W_tcp;
    in.holes.push_back(rh);
  }
  addPartFrameAndSplit(in, c);  // report.hpp: part frame and the δrobot split (issue 14)
  return renderReport(in);
}

std::string compensationTargets(const CompensationResult& r, const std::string& program_path,
                                bool csv) {
  if (csv) return targetsCsv(r);
  Json root = Json::object();
  root.set("robot", Json::str(r.context.robot.card.name));
  root.set("cell", Json::str(r.context.cell.name));
  root.set("program", Json::str(fileName(program_path)));
  root.set("orientation", Json::str(r.orientation));
  Json hs = Json::array();
  for (size_t i = 0; i < r.holes.size(); ++i) {
    hs.push(finiteOrFailed(targetJson(r, i), r.holes[i].id, r.context.job.requests[i].line));
  }
  root.set("holes", hs);
  return root.dump();
}

std::string compensationReport(const CompensationResult& r, const std::string& program_path) {
  const PredictionContext& c = r.context;
  ReportInput in = reportHeader(
      c, "roprec compensation — " + fileName(program_path) + " (" + r.orientation + ")");
  in.program = program_path;
  in.compensation = true;
  std::vector<HolePrediction> after;
  after.reserve(r.holes.size());
  for (const HoleCompensation& h : r.holes) after.push_back(h.ok ? h.after : h.before);
  in.summary = summarize(after);
  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HoleCompensation& h = r.holes[i];
    ReportHole rh;
    rh.prediction = &h.before;
    rh.T_W_tcp = c.job.requests[i].T_W_tcp;
    if (h.ok) {
      rh.residual_um = perpNorm(h.residual, h.T_nominal.linear().col(2)) * 1e6;
      rh.T_W_programmed = h.T_programmed;
      rh.rotation_about_axis_deg = h.psi / kDeg;
      rh.after = &h.after;
      rh.config_after = h.config_text;  // issue 14: flags before → after
    }
    in.holes.push_back(rh);
  }
  addPartFrameAndSplit(in, c);  // report.hpp: part frame and the δrobot split (issue 14)
  return renderReport(in);
}

std::string millingTargetsJson(const MillingCompensationResult& r,
                               const std::string& program_path) {
  const PredictionContext& c = r.context;
  Json root = Json::object();
  root.set("robot", Json::str(c.robot.card.name));
  root.set("cell", Json::str(c.cell.name));
  root.set("program", Json::str(fileName(program_path)));
  root.set("process", Json::str(c.process_description));
  Json ps = Json::array();
  for (size_t i = 0; i < r.points_comp.size(); ++i) {
    const PathPointCompensation& p = r.points_comp[i];
    Json j = Json::object();
    j.set("point", Json::integer(static_cast<std::int64_t>(i + 1)));
    j.set("ok", Json::boolean(p.ok));
    if (!p.reason.empty()) j.set("reason", Json::str(p.reason));
    j.set("target", Json::str(c.job.program->targets()[static_cast<size_t>(r.targets[i])].name));
    j.set("nominal", poseJsonContract(r.points[i]));
    j.set("cutting", Json::boolean(p.cutting));
    j.set("cutting_reason", Json::str(p.cutting_reason));
    Json b = Json::object();
    b.set("deviation_um", Json::vector(p.deviation_before * 1e6, 3));
    b.set("coupling_status", Json::str(p.before_status));
    b.set("coupling_iterations", Json::integer(p.before_iterations));
    b.set("coupling_residual_um", Json::number(p.before_residual * 1e6, 4));
    b.set("loop_gain", Json::number(p.before_loop_gain, 4));
    b.set("force_N", Json::vector(p.before_force, 3));
    j.set("before", b);
    Json pr = poseJsonContract(p.T_programmed);
    pr.set("joints_deg", Json::vector(p.theta_cmd / kDeg, 6));
    pr.set("config", Json::str(p.config_text));
    j.set("programmed", pr);
    j.set("residual_um", Json::number(p.residual.norm() * 1e6, 4));
    j.set("force_N", Json::vector(p.force, 3));
    Json cp = Json::object();
    cp.set("converged", Json::boolean(p.coupling_converged));
    cp.set("status", Json::str(p.coupling_status));
    cp.set("iterations", Json::integer(p.coupling_iterations));
    cp.set("residual_um", Json::number(p.coupling_residual * 1e6, 4));
    cp.set("loop_gain", Json::number(p.loop_gain, 4));
    cp.set("force_fixed_point_iterations", Json::integer(p.force_iterations));
    j.set("coupling", cp);
    ps.push(j);
  }
  root.set("points", ps);
  return root.dump();
}

}  // namespace roprec::api
