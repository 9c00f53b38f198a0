/// \file exports.cpp
/// The texts a job writes: prediction JSON and report, corrected-target exports (CSV/JSON),
/// compensation report, milling path export (docs/contract.md).
#include <cmath>
#include <filesystem>
#include <memory>
#include <string_view>

#include "compensator/precision/parallel.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/report_input.hpp"
#include "plugin/api/robots.hpp"
#include "plugin/report/milling_output.hpp"
#include "plugin/report/prediction_json.hpp"

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
    if (n.rfind("drill: ", 0) == 0) in.process += "; " + n;  // holes the single drill drills
  }
  in.card_estimates = cardEstimates(c.robot.card);
  in.uncertainty_method = uncertaintyMethodText(c.model.uncertainty);
  in.uncertainty_source = c.model.uncertainty.source;
  in.default_tolerance_mm = c.cell.tolerance_mm;
  in.card = &c.robot.card;  // joints in the controller's convention
  in.generator = std::string("roprec ") + version();
  return in;
}

// ---- corrected-target export, one row / object per hole

/// The nominal pose of hole h (request q): the chosen one when compensated, else the programmed
/// one.
const Pose& nominalOf(const HoleCompensation& h, const HoleRequest& q) {
  return h.ok ? h.T_nominal : q.T_W_tcp;
}

void csvNumber(std::string& s, double v, int decimals) {
  s += ',';
  if (std::isfinite(v)) {
    appendNumber(s, v, decimals);
  } else {
    s += numberText(v);  // formatNumber's words, as before
  }
}

void csvQuaternion(std::string& s, const Mat3& R) {
  const Eigen::Quaterniond q = quaternionFromRotation(R);
  csvNumber(s, q.w(), 9);
  csvNumber(s, q.x(), 9);
  csvNumber(s, q.y(), 9);
  csvNumber(s, q.z(), 9);
}

/// ,"text" with the text's double quotes doubled (RFC 4180).
void csvQuoted(std::string& s, std::string_view text) {
  s += ",\"";
  for (const char c : text) {
    if (c == '"') s += '"';
    s += c;
  }
  s += '"';
}

void csvRow(std::string& s, const HoleCompensation& h, const HoleRequest& q,
            const RobotCard& card) {
  const Pose& N = nominalOf(h, q);
  const Pose& P = h.ok ? h.T_programmed : N;
  s += h.id;
  s += h.ok ? ",compensated" : ",original-kept";
  for (int k = 0; k < 3; ++k) csvNumber(s, N.translation()[k] * 1e3, 6);
  csvQuaternion(s, N.linear());
  for (int k = 0; k < 3; ++k) csvNumber(s, h.before.d_work[k] * 1e6, 3);
  for (int k = 0; k < 3; ++k) csvNumber(s, h.before.d_rot[k] * 1e6, 3);
  for (int k = 0; k < 3; ++k) csvNumber(s, P.translation()[k] * 1e3, 6);
  csvQuaternion(s, P.linear());
  for (int k = 0; k < 6; ++k) csvNumber(s, (h.ok ? h.theta_cmd[k] : h.before.joints[k]) / kDeg, 6);
  s += ",\"";
  s += h.ok ? h.config_text : h.before.config;
  s += '"';
  csvNumber(s, h.psi / kDeg, 4);
  const Vec3 a = N.linear().col(2);
  csvNumber(s, h.ok ? perpNorm(h.residual, a) * 1e6 : h.before.position_error * 1e6, 4);
  const HolePrediction& u = h.ok ? h.after : h.before;
  csvNumber(s, u.U_robot * 1e6, 3);
  csvNumber(s, u.U_mach * 1e6, 3);
  csvNumber(s, u.U_work * 1e6, 3);
  csvNumber(s, u.k, 4);
  s += ',';
  s += verdictName(u.verdict);
  csvQuoted(s, h.reason);
  // the joints as the controller shows them, why the rotation and the flags changed
  const Vec6 q_ctrl = toControllerJoints(card, h.ok ? h.theta_cmd : h.before.joints);
  for (int k = 0; k < 6; ++k) csvNumber(s, q_ctrl[k] / kDeg, 6);
  csvQuoted(s, h.ok ? h.psi_reason.view() : std::string_view());
  csvQuoted(s, h.config_before);
  s += h.ok && h.config_changed ? ",1" : ",0";
  csvQuoted(s, h.ok ? h.config_reason.view() : std::string_view());
  s += '\n';
}

constexpr size_t kChunk = size_t{64} * 1024;  ///< bytes handed to a ByteSink at a time

/// The header row of the CSV export.
const char* const kTargetsCsvHeader =
    "id,status,nominal_x_mm,nominal_y_mm,nominal_z_mm,nominal_qw,nominal_qx,nominal_qy,nominal_"
    "qz,"
    "before_dx_um,before_dy_um,before_dz_um,before_rx_urad,before_ry_urad,before_rz_urad,"
    "programmed_x_mm,programmed_y_mm,programmed_z_mm,programmed_qw,programmed_qx,programmed_qy,"
    "programmed_qz,"
    "j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg,config,rotation_about_axis_deg,residual_um,U_"
    "robot_um,U_mach_um,"
    "U_work_um,k,verdict,reason,j1_ctrl_deg,j2_ctrl_deg,j3_ctrl_deg,j4_ctrl_deg,j5_ctrl_deg,"
    "j6_ctrl_deg,rotation_reason,config_before,config_changed,config_reason\n";

/// The CSV rows of holes[k] (request q[k]) to `sink`: blocks of rows formatted on the workers
/// (the calling thread alone for threads <= 1), a round of them at a time, written in order.
void csvRows(std::span<const HoleCompensation> holes, std::span<const HoleRequest> q,
             const RobotCard& card, const ByteSink& sink, int threads) {
  const size_t n = holes.size();
  constexpr size_t kRows = 128;
  const size_t blocks = (n + kRows - 1) / kRows;
  const size_t round = 8 * static_cast<size_t>(std::max(1, threads));
  std::vector<std::string> text(std::min(blocks, round));
  for (size_t b0 = 0; b0 < blocks; b0 += round) {
    const size_t m = std::min(round, blocks - b0);
    parallelFor(m, threads, [&](int, size_t k) {
      text[k].clear();
      const size_t first = (b0 + k) * kRows;
      for (size_t i = first; i < std::min(n, first + kRows); ++i)
        csvRow(text[k], holes[i], q[i], card);
    });
    for (size_t k = 0; k < m; ++k) sink(text[k]);
  }
}

void targetsCsv(const CompensationResult& r, const ByteSink& sink, int threads) {
  sink(kTargetsCsvHeader);
  csvRows(r.holes, r.context.job.requests, r.context.robot.card, sink, threads);
}

/// The item written instead of one whose numbers are not all finite (a bug or an input that
/// escaped the range checks): it is reported as failed on its own instead of poisoning the whole
/// output. The same members as finiteOrFailed().
void failedItem(JsonWriter& w, const std::string& id, int line) {
  w.beginObject();
  w.key("id");
  w.str(id);
  if (line > 0) {
    w.key("line");
    w.integer(line);
  }
  w.key("status");
  w.str("failed");
  w.key("reason");
  w.str(
      "internal error: the result of this hole is not a finite number, so it is not reported "
      "(please report this input)");
  w.endObject();
}

/// Writes one array item with `write`; a non-finite number in it replaces it by failedItem().
template <class F>
void itemOrFailed(JsonWriter& w, const std::string& id, int line, F&& write) {
  const JsonWriter::Mark m = w.mark();
  try {
    write();
  } catch (const JsonNonFinite&) {
    w.rewind(m);
    failedItem(w, id, line);
  }
}

void poseContract(JsonWriter& w, const Pose& T) {
  w.key("position_mm");
  w.numbers(T.translation() * 1e3, 6);
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  w.key("quaternion_wxyz");
  w.numbers(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9);
}

void uncertaintyTarget(JsonWriter& w, const HolePrediction& u) {
  w.beginObject();
  w.key("U_robot");
  w.number(u.U_robot * 1e6, 3);
  w.key("U_mach");
  w.number(u.U_mach * 1e6, 3);
  w.key("U_work");
  w.number(u.U_work * 1e6, 3);
  w.key("U_work_anisotropic");
  w.number(u.U_work_exact * 1e6, 3);
  w.key("k");
  w.number(u.k, 4);
  w.endObject();
}

/// "before": the deviation and the verdict of the hole as programmed.
void targetBefore(JsonWriter& w, const HoleCompensation& h) {
  w.key("before");
  w.beginObject();
  w.key("deviation_um");
  w.beginObject();
  w.key("translation");
  w.numbers(h.before.d_work * 1e6, 3);
  w.key("rotation_urad");
  w.numbers(h.before.d_rot * 1e6, 3);
  w.endObject();
  w.key("verdict");
  w.str(verdictName(h.before.verdict));
  w.endObject();
}

/// "programmed": the compensated pose, its joints and flags.
void targetProgrammed(JsonWriter& w, const RobotCard& card, const HoleCompensation& h) {
  w.key("programmed");
  w.beginObject();
  poseContract(w, h.T_programmed);
  w.key("joints_deg");
  w.numbers(h.theta_cmd / kDeg, 6);
  w.key("controller_joints_deg");
  w.numbers(toControllerJoints(card, h.theta_cmd) / kDeg, 6);
  w.key("config");
  w.str(h.config_text);
  w.endObject();
}

/// What a compensated hole adds: the programmed target, the rotation about the drill axis, the
/// residual, whether the branch and flags changed and why, stiffest's gain, a note.
void targetCompensation(JsonWriter& w, const RobotCard& card, const HoleCompensation& h,
                        const Pose& N) {
  targetProgrammed(w, card, h);
  w.key("rotation_about_axis_deg");
  w.number(h.psi / kDeg, 4);
  w.key("residual_um");
  w.number(perpNorm(h.residual, N.linear().col(2)) * 1e6, 4);
  w.key("residual_vector_um");
  w.numbers(h.residual * 1e6, 4);
  w.key("branch_changed");
  w.boolean(h.branch_changed);
  // why the rotation about the drill axis / the flags changed, stiffest's gain
  if (!h.psi_reason.empty()) {
    w.key("rotation_reason");
    w.str(h.psi_reason);
  }
  w.key("config_before");
  w.str(h.config_before);
  w.key("config_changed");
  w.boolean(h.config_changed);
  if (!h.config_reason.empty()) {
    w.key("config_reason");
    w.str(h.config_reason);
  }
  if (std::isfinite(h.U_work_keep)) {
    w.key("U_work_keep_um");
    w.number(h.U_work_keep * 1e6, 3);
    w.key("U_work_gain_um");
    w.number((h.U_work_keep - h.after.U_work_exact) * 1e6, 3);
  }
  if (!h.note.empty()) {
    w.key("note");
    w.str(h.note);
  }
}

void targetJson(JsonWriter& w, const HoleCompensation& h, const HoleRequest& q,
                const RobotCard& card) {
  w.beginObject();
  w.key("id");
  w.str(h.id);
  w.key("status");
  w.str(h.ok ? "compensated" : "original-kept");
  if (!h.ok) {
    w.key("reason");
    w.str(h.reason);
  }
  const Pose& N = nominalOf(h, q);
  w.key("nominal");
  w.beginObject();
  poseContract(w, N);
  w.endObject();
  targetBefore(w, h);
  if (h.ok) targetCompensation(w, card, h, N);
  const HolePrediction& u = h.ok ? h.after : h.before;
  w.key("uncertainty_um");
  uncertaintyTarget(w, u);
  w.key("verdict");
  w.str(verdictName(u.verdict));
  w.endObject();
}

/// An export's first members: the robot card's name, the cell's and the program's file name.
void jobIdentityJson(JsonWriter& w, const PredictionContext& c, const std::string& program_path) {
  w.key("robot");
  w.str(c.robot.card.name);
  w.key("cell");
  w.str(c.cell.name);
  w.key("program");
  w.str(fileName(program_path));
}

/// The JSON export's members before the holes, up to the opening of the "holes" array.
void targetsJsonHead(JsonWriter& w, const PredictionContext& c, const std::string& orientation,
                     const std::string& program_path) {
  w.out().reserve(kChunk + 8192);
  w.beginObject();
  jobIdentityJson(w, c, program_path);
  w.key("orientation");
  w.str(orientation);
  w.key("holes");
  w.beginArray();
}

/// The items of holes[k] (request q[k]) into the "holes" array, handed to `sink` about kChunk
/// bytes at a time.
void targetsJsonItems(JsonWriter& w, std::span<const HoleCompensation> holes,
                      std::span<const HoleRequest> q, const RobotCard& card, const ByteSink& sink) {
  for (size_t i = 0; i < holes.size(); ++i) {
    itemOrFailed(w, holes[i].id, q[i].line, [&] { targetJson(w, holes[i], q[i], card); });
    if (w.out().size() >= kChunk) {
      sink(w.out());
      w.out().clear();
    }
  }
}

/// The end of the JSON export (the "holes" array closed), handed to `sink`.
void targetsJsonEnd(JsonWriter& w, const ByteSink& sink) {
  w.endArray();
  w.endObject();
  w.finish();
  sink(w.out());
  w.out().clear();
}

void targetsJson(const CompensationResult& r, const std::string& program_path,
                 const ByteSink& sink) {
  JsonWriter w;
  targetsJsonHead(w, r.context, r.orientation, program_path);
  targetsJsonItems(w, r.holes, r.context.job.requests, r.context.robot.card, sink);
  targetsJsonEnd(w, sink);
}

/// "nominal": the hole's frame (position, surface, bottom, orientation, axis).
void predictionNominal(JsonWriter& w, const HoleRequest& r) {
  w.key("nominal");
  w.beginObject();
  w.key("position_mm");
  w.numbers(r.T_W_tcp.translation() * 1e3, 6);
  if (r.surface_W) {
    w.key("surface_mm");
    w.numbers(*r.surface_W * 1e3, 6);
  }
  w.key("bottom_mm");
  w.numbers(r.T_W_tcp.translation() * 1e3, 6);
  const Eigen::Quaterniond q = quaternionFromRotation(r.T_W_tcp.linear());
  w.key("quaternion_wxyz");
  w.numbers(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9);
  w.key("axis");
  w.numbers(r.T_W_tcp.linear().col(2), 9);
  w.endObject();
}

/// The posture the IK found: joints (URDF and controller), flags, branch.
void predictionPosture(JsonWriter& w, const HolePrediction& h, const RobotCard& card) {
  w.key("joints_deg");
  w.numbers(h.joints / kDeg, 6);
  w.key("controller_joints_deg");
  w.numbers(toControllerJoints(card, h.joints) / kDeg, 6);
  if (!h.config.empty()) {
    w.key("config");
    w.str(h.config);
  }
  w.key("branch");
  w.integer(h.branch);
}

/// "deviation_um" of a predicted hole.
void predictionDeviation(JsonWriter& w, const HolePrediction& h) {
  w.key("deviation_um");
  w.beginObject();
  w.key("robot");
  w.numbers(h.d_robot * 1e6, 3);
  w.key("mach");
  w.numbers(h.d_mach * 1e6, 3);
  w.key("work");
  w.numbers(h.d_work * 1e6, 3);
  w.key("robot_rotation_urad");
  w.numbers(h.d_rot * 1e6, 3);
  w.key("work_tool_xy");
  w.numbers(h.e_tool * 1e6, 3);
  w.key("position_error");
  w.number(h.position_error * 1e6, 3);
  w.key("axis_tilt_urad");
  w.number(h.axis_tilt * 1e6, 3);
  if (h.nominal_axis_error) {
    w.key("from_nominal_axis");
    w.number(*h.nominal_axis_error * 1e6, 4);
  }
  w.endObject();
}

/// "standard_per_axis": every budget term's standard uncertainty; "term_sources" when known.
void budgetTerms(JsonWriter& w, const HolePrediction& h) {
  w.key("standard_per_axis");
  w.beginObject();
  bool any_source = false;
  for (const BudgetTerm& t : h.budget) {
    w.key(t.name);
    w.number(t.u * 1e6, 3);
    any_source |= t.source != nullptr;
  }
  w.endObject();
  if (any_source) {
    w.key("term_sources");
    w.beginObject();
    for (const BudgetTerm& t : h.budget) {
      if (t.source == nullptr) continue;
      w.key(t.name);
      w.str(t.source);
    }
    w.endObject();
  }
}

/// "uncertainty_um" of a predicted hole: expanded, per term, the process shares.
void predictionUncertainty(JsonWriter& w, const HolePrediction& h) {
  w.key("uncertainty_um");
  w.beginObject();
  w.key("U_robot");
  w.number(h.U_robot * 1e6, 3);
  w.key("U_mach");
  w.number(h.U_mach * 1e6, 3);
  w.key("U_work");
  w.number(h.U_work * 1e6, 3);
  w.key("k");
  w.number(h.k, 4);
  w.key("coverage");
  w.str("2-D radial 95 % (Rayleigh)");
  w.key("U_work_anisotropic");
  w.number(h.U_work_exact * 1e6, 3);
  budgetTerms(w, h);
  w.key("process_share");
  w.number(h.process_share, 4);
  w.key("process_force_share");
  w.number(h.process_force_share, 4);
  w.endObject();
}

/// The process force and the equilibrium of the deflection.
void predictionLoad(JsonWriter& w, const HolePrediction& h) {
  w.key("process_force_N");
  w.numbers(h.force_base, 2);
  w.key("equilibrium");
  w.beginObject();
  w.key("converged");
  w.boolean(h.deflection.converged);
  w.key("iterations");
  w.integer(h.deflection.iterations);
  w.endObject();
}

/// One hole of the prediction JSON: the same members, in the same order, as holeJson()
/// (prediction_setup.cpp, the tree the C and Python hosts build; tests/streaming_output_test.cpp
/// compares the two byte for byte).
void predictionHole(JsonWriter& w, const HolePrediction& h, const HoleRequest& r,
                    const RobotCard& card) {
  w.beginObject();
  w.key("id");
  w.str(h.id);
  if (r.line > 0) {
    w.key("line");
    w.integer(r.line);
  }
  if (!r.evidence.empty()) {
    w.key("evidence");
    w.str(r.evidence);
  }
  predictionNominal(w, r);
  w.key("diameter_mm");
  w.number(h.diameter * 1e3, 3);
  w.key("depth_mm");
  w.number(h.depth * 1e3, 3);
  if (statesOwnProcess(r)) {
    w.key("drill");
    w.beginObject();
    if (!r.tool.empty()) {
      w.key("tool");
      w.str(r.tool);
    }
    w.key("feed_mm_per_rev");
    w.number(h.feed * 1e3, 4);
    w.key("spindle_rpm");
    w.number(h.spindle_rpm, 1);
    w.endObject();
  }
  if (h.status == HoleStatus::kOk || h.status == HoleStatus::kNotConverged ||
      h.status == HoleStatus::kSingular) {
    predictionPosture(w, h, card);
  }
  if (h.status == HoleStatus::kOk) {
    predictionDeviation(w, h);
    predictionUncertainty(w, h);
    predictionLoad(w, h);
  }
  w.key("tolerance_mm");
  w.number(h.tolerance * 1e3, 4);
  w.key("verdict");
  w.str(verdictName(h.verdict));
  if (!h.reason.empty()) {
    w.key("reason");
    w.str(h.reason);
  }
  w.key("mc_time_s");
  w.number(h.mc_time, 3);
  w.endObject();
}

}  // namespace

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
    hs.push(finiteOrFailed(holeJson(r.holes[i], c.job.requests[i], &c.robot.card), r.holes[i].id,
                           c.job.requests[i].line));
  }
  root.set("holes", hs);
  root.set("summary", summaryJson(r.summary));
  return root;
}

namespace {

/// The header of a prediction's report: title, robot with its model, the job's summary.
ReportInput predictionReportHeader(const PredictionContext& c, const CapabilitySummary& summary) {
  ReportInput in = reportHeader(c, "roprec prediction — " + fileName(c.job.path));
  if (!c.robot.card.model.empty())
    in.robot += " (" + vendorName(c.robot.card.vendor) + " " + c.robot.card.model + ")";
  in.summary = summary;
  return in;
}

}  // namespace

std::string predictionReport(const PredictionResult& r, int threads) {
  const PredictionContext& c = r.context;
  ReportInput in = predictionReportHeader(c, r.summary);
  for (size_t i = 0; i < r.holes.size(); ++i) {
    ReportHole rh;
    rh.prediction = &r.holes[i];
    rh.T_W_tcp = c.job.requests[i].T_W_tcp;
    in.holes.push_back(std::move(rh));
  }
  // report_input.hpp: part frame and the δrobot split (the report shows no process_alone)
  addPartFrameAndSplit(in, c, threads, false);
  return renderReport(in);
}

std::string compensationTargets(const CompensationResult& r, const std::string& program_path,
                                bool csv) {
  std::string out;
  writeCompensationTargets(r, program_path, csv, [&](std::string_view b) { out += b; });
  return out;
}

CompensationTargetsStream::CompensationTargetsStream(const PredictionContext& c,
                                                     const std::string& orientation,
                                                     const std::string& program_path, bool csv,
                                                     ByteSink sink, int threads)
    : csv_(csv), threads_(threads), sink_(std::move(sink)), card_(c.robot.card) {
  if (csv_) {
    sink_(kTargetsCsvHeader);
  } else {
    targetsJsonHead(w_, c, orientation, program_path);
  }
}

void CompensationTargetsStream::holes(std::span<const HoleCompensation> h,
                                      std::span<const HoleRequest> q) {
  if (csv_) {
    csvRows(h, q, card_, sink_, threads_);
  } else {
    targetsJsonItems(w_, h, q, card_, sink_);
  }
}

void CompensationTargetsStream::finish() {
  if (!csv_) targetsJsonEnd(w_, sink_);
}

void writeCompensationTargets(const CompensationResult& r, const std::string& program_path,
                              bool csv, const ByteSink& sink, int threads) {
  if (csv) {
    targetsCsv(r, sink, threads);
  } else {
    targetsJson(r, program_path, sink);
  }
}

// ---- streamed prediction report

PredictionReportStream::PredictionReportStream(const PredictionContext& c, int threads)
    : splitter_(c.model, c.tool, std::max(1, threads), false),  // no process_alone: not shown
      workers_(std::max(1, threads)),
      card_(c.robot.card) {
  const size_t n = c.job.deferred ? c.job.hole_count : c.job.requests.size();
  if (n > kReportAggregateAbove) {
    rows_.emplace(&card_);
    mapped_.reserve(n);
  } else {
    holes_.reserve(n);
  }
}

void PredictionReportStream::holes(std::span<const HolePrediction> h,
                                   std::span<const HoleRequest> r, int threads) {
  const int t = std::min(threads, workers_);
  // a large job: the block's records, released once its rows are rendered and its totals counted
  const size_t first = rows_ ? 0 : holes_.size(), at = mapped_.size();
  if (holes_.size() < first + h.size()) holes_.resize(first + h.size());
  if (rows_) mapped_.resize(at + h.size());
  parallelFor(h.size(), t, [&](int w, size_t k) {
    PredictedHole& ph = holes_[first + k];
    reportPrediction(h[k], ph.prediction);
    ph.position = r[k].T_W_tcp.translation();
    ph.axis = r[k].T_W_tcp.linear().col(2);
    ph.split = splitter_.split(r[k], h[k].status, h[k].joints, h[k].d_robot, w);
    if (rows_) mapped_[at + k] = {ph.prediction, ph.position, ph.axis};
  });
  if (!rows_) return;
  const std::span<const PredictedHole> block = std::span(holes_).first(h.size());
  totals_.add(block);
  rows_->render(block, at, t, rows_ahead_);
}

ReportInput PredictionReportStream::input(const PredictionResult& r) {
  ReportInput in = predictionReportHeader(r.context, r.summary);
  setPartFrame(in, r.context, r.frames);
  in.threads = workers_;
  if (rows_) {  // a large job: its holes as the maps need them, its rows rendered ahead
    in.mapped = std::move(mapped_);
    in.totals = std::move(totals_);
    in.rows_ahead = std::move(rows_ahead_);
  } else {
    in.predicted = std::move(holes_);
  }
  return in;
}

std::string PredictionReportStream::finish(const PredictionResult& r) {
  return renderReport(input(r));
}

void PredictionReportStream::finish(const PredictionResult& r, const ByteSink& sink) {
  renderReport(input(r), sink);
}

// ---- streamed prediction JSON

PredictionJsonStream::PredictionJsonStream(const PredictionContext& c, ByteSink sink)
    : sink_(std::move(sink)), card_(c.robot.card) {
  w_.out().reserve(kChunk + 8192);
  w_.beginObject();
  w_.key("robot");
  w_.str(c.robot.card.name);
  w_.key("cell");
  w_.str(c.cell.name);
  const std::string program = fileName(c.job.path);
  w_.key("program");
  w_.str(program);
  w_.key("process");
  w_.str(c.process_description);
  w_.key("uncertainty_inputs");
  w_.value(uncertaintyInputsJson(c.model.uncertainty));
  w_.key("notes");
  w_.strings(c.job.notes);
  w_.key("holes");
  w_.beginArray();
}

void PredictionJsonStream::item(JsonWriter& w, const HolePrediction& h, const HoleRequest& r,
                                const RobotCard& card) {
  itemOrFailed(w, h.id, r.line, [&] { predictionHole(w, h, r, card); });
}

void PredictionJsonStream::hole(const HolePrediction& h, const HoleRequest& r) {
  item(w_, h, r, card_);
  drain(false);
}

void PredictionJsonStream::holes(std::span<const HolePrediction> h, std::span<const HoleRequest> r,
                                 int threads) {
  constexpr size_t kRun = 32;  // holes per text (about 60 kB)
  const size_t runs = (h.size() + kRun - 1) / kRun;
  texts_.resize(runs);
  parallelFor(runs, threads, [&](int, size_t k) {
    JsonWriter w = w_.itemWriter(k * kRun);
    w.out().swap(texts_[k]);  // the run's buffer of the block before, reused
    w.out().clear();
    for (size_t i = k * kRun; i < std::min(h.size(), (k + 1) * kRun); ++i)
      item(w, h[i], r[i], card_);
    w.out().swap(texts_[k]);
  });
  // each run's text goes to the sink as it is (not copied behind the writer's text first)
  for (size_t k = 0; k < runs; ++k) {
    drain(true);
    sink_(texts_[k]);
    w_.appendItems({}, std::min(kRun, h.size() - k * kRun));
  }
}

void PredictionJsonStream::finish(const CapabilitySummary& s) {
  w_.endArray();
  w_.key("summary");
  w_.value(summaryJson(s));
  w_.endObject();
  w_.finish();
  drain(true);
}

void PredictionJsonStream::drain(bool all) {
  if (w_.out().empty() || (!all && w_.out().size() < kChunk)) return;
  sink_(w_.out());
  w_.out().clear();
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
      rh.config_after = h.config_text;  // flags before → after, and why
      rh.config_before = h.config_before;
      rh.rotation_reason = h.psi_reason.str();
      rh.config_reason = h.config_reason.str();
    }
    in.holes.push_back(rh);
  }
  addPartFrameAndSplit(in, c);  // report_input.hpp: part frame and the δrobot split
  return renderReport(in);
}

namespace {

/// Path point i of the milling export as a JSON object.
Json millingPointJson(const MillingCompensationResult& r, size_t i) {
  const PredictionContext& c = r.context;
  const PathPointCompensation& p = r.point(i);
  Json j = Json::object();
  j.set("point", Json::integer(static_cast<std::int64_t>(i + 1)));
  j.set("ok", Json::boolean(p.ok));
  if (!p.reason.empty()) j.set("reason", Json::str(p.reason));
  j.set("target", Json::str(r.targetName(i)));
  j.set("nominal", poseJsonContract(r.nominal(i)));
  j.set("cutting", Json::boolean(p.cutting));
  j.set("cutting_reason", Json::str(p.cutting_reason));
  Json b = Json::object();
  b.set("deviation_um", Json::vector(p.deviation_before * 1e6, 3));
  b.set("coupling_status", Json::str(p.before_status));
  b.set("coupling_iterations", Json::integer(p.before_iterations));
  b.set("coupling_residual_um", Json::number(p.before_residual * 1e6, 4));
  b.set("loop_gain", Json::number(p.before_loop_gain, 4));
  b.set("force_N", Json::vector(p.before_force, 3));
  const std::optional<MillingEngagement>& engaged = r.engagement(i);  // box stock
  if (p.cutting) {
    b.set("surface_error_um", Json::number(p.surface_error_before * 1e6, 3));
    if (engaged) {
      b.set("ae_mm", Json::number(p.ae * 1e3, 4));
      b.set("ap_mm", Json::number(p.ap * 1e3, 4));
    }
  }
  j.set("before", b);
  Json pr = poseJsonContract(p.T_programmed);
  pr.set("joints_deg", Json::vector(p.theta_cmd / kDeg, 6));
  pr.set("controller_joints_deg",
         Json::vector(toControllerJoints(c.robot.card, p.theta_cmd) / kDeg, 6));
  pr.set("config", Json::str(p.config_text));
  j.set("programmed", pr);
  j.set("residual_um", Json::number(p.residual.norm() * 1e6, 4));
  if (p.cutting_after) {
    j.set("surface_error_um", Json::number(p.surface_error * 1e6, 4));
    if (engaged) {
      j.set("ae_mm", Json::number(p.ae_after * 1e3, 4));
      j.set("ap_mm", Json::number(p.ap_after * 1e3, 4));
      j.set("programmed_ae_mm", Json::number(engaged->ae * 1e3, 4));
      j.set("programmed_ap_mm", Json::number(engaged->ap * 1e3, 4));
    }
  }
  j.set("force_N", Json::vector(p.force, 3));
  Json cp = Json::object();
  cp.set("converged", Json::boolean(p.coupling_converged));
  cp.set("status", Json::str(p.coupling_status));
  cp.set("iterations", Json::integer(p.coupling_iterations));
  cp.set("residual_um", Json::number(p.coupling_residual * 1e6, 4));
  cp.set("loop_gain", Json::number(p.loop_gain, 4));
  cp.set("force_fixed_point_iterations", Json::integer(p.force_iterations));
  j.set("coupling", cp);
  if (p.cutting) j.set("stability", pathPointStabilityJson(p, millOf(r, i).cut.ap));
  return j;
}

/// The CSV row of path point i.
void millingPointCsv(const MillingCompensationResult& r, size_t i, std::string& s) {
  const PathPointCompensation& p = r.point(i);
  s += std::to_string(i + 1);
  csvQuoted(s, r.targetName(i));
  s += "," + std::to_string(r.targetLine(i)) + "," + (p.cutting ? "1" : "0") + "," +
       (p.ok ? "1" : "0");
  const Vec3 x = p.T_programmed.translation() * 1e3;
  for (int k = 0; k < 3; ++k) s += "," + formatNumber(x[k], 5);
  s += "," + formatNumber(p.deviation_before.norm() * 1e6, 3) + "," +
       formatNumber(p.residual.norm() * 1e6, 4) + "," +
       (p.cutting ? formatNumber(p.surface_error_before * 1e6, 3) : std::string()) + "," +
       (p.cutting_after ? formatNumber(p.surface_error * 1e6, 4) : std::string());
  for (int k = 0; k < 3; ++k) s += "," + formatNumber(p.force[k], 3);
  csvQuoted(s, p.coupling_status);
  const bool bounded = p.cutting && p.stability_checked && p.stability_bounded;
  s += "," + (bounded ? formatNumber(p.ap_limit * 1e3, 4) : std::string()) + "," +
       (bounded ? formatNumber(p.ap_limit / millOf(r, i).cut.ap, 4) : std::string());
  csvQuoted(s, p.reason);
  s += "\n";
}

constexpr size_t kSinkPiece = 64 * 1024;

}  // namespace

MillingTargetsStream::MillingTargetsStream(bool csv, std::string program_path, ByteSink sink)
    : csv_(csv), program_path_(std::move(program_path)), sink_(std::move(sink)) {}

void MillingTargetsStream::begin(const MillingCompensationResult& r) {
  begun_ = true;
  if (csv_) {
    s_ = "point,target,line,cutting,ok,x_mm,y_mm,z_mm,deviation_before_um,residual_um,"
         "surface_error_before_um,surface_error_um,Fx_N,Fy_N,Fz_N,coupling,ap_limit_mm,"
         "chatter_margin,reason\n";
    return;
  }
  const PredictionContext& c = r.context;
  w_.beginObject();
  jobIdentityJson(w_, c, program_path_);
  w_.key("process");
  w_.str(c.process_description);
  w_.key("points");
  w_.beginArray();
}

void MillingTargetsStream::points(const MillingCompensationResult& r) {
  if (!begun_) begin(r);
  const size_t end = r.first + r.points_comp.size();
  std::string piece;
  for (size_t i = r.first; i < end; ++i) {
    if (csv_) {
      millingPointCsv(r, i, s_);
      if (s_.size() >= kSinkPiece) {
        sink_(s_);
        s_.clear();
      }
      continue;
    }
    w_.value(millingPointJson(r, i));  // one point's tree at a time
    if (w_.out().size() >= kSinkPiece) {
      w_.take(piece);
      sink_(piece);
    }
  }
}

void MillingTargetsStream::finish(const MillingCompensationResult& r) {
  if (!begun_) begin(r);
  if (csv_) {
    sink_(s_);
    s_.clear();
    return;
  }
  w_.endArray();
  w_.endObject();
  w_.finish();
  std::string piece;
  w_.take(piece);
  sink_(piece);
}

void writeMillingTargets(const MillingCompensationResult& r, const std::string& program_path,
                         bool csv, const ByteSink& sink) {
  MillingTargetsStream out(csv, program_path, sink);
  out.points(r);
  out.finish(r);
}

std::string millingTargetsCsv(const MillingCompensationResult& r) {
  std::string s;
  writeMillingTargets(r, "", true, [&s](std::string_view v) { s += v; });
  return s;
}

std::string millingTargetsJson(const MillingCompensationResult& r,
                               const std::string& program_path) {
  std::string s;
  writeMillingTargets(r, program_path, false, [&s](std::string_view v) { s += v; });
  return s;
}

}  // namespace roprec::api
