#include "plugin/api/verify.hpp"

#include <cmath>
#include <filesystem>

#include "compensator/precision/card_writer.hpp"
#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"

namespace roprec::api {
namespace {

namespace fs = std::filesystem;

std::string baseName(const std::string& path) { return fs::path(path).filename().string(); }

/// The nominal hole of request i: the hole list's when one was matched (its point and axis; the
/// program's rotation about the axis when the axes agree), else the program's drill point.
Pose nominalHole(const PredictionContext& c, size_t i) {
  if (i < c.job.sources.size() && c.job.sources[i].T_W_tcp_spec)
    return *c.job.sources[i].T_W_tcp_spec;
  const HoleRequest& q = c.job.requests[i];
  if (!q.nominal_axis) return q.T_W_tcp;
  Pose T = q.T_W_tcp;
  const Vec3 z = q.nominal_axis->second.normalized();
  if (T.linear().col(2).dot(z) < 1.0 - 1e-9) T.linear() = holeFrame(z);
  T.translation() = q.nominal_axis->first;
  return T;
}

std::vector<postproc::ProgramHoleRef> programRefs(const PredictionContext& c) {
  std::vector<postproc::ProgramHoleRef> refs;
  const Pose T_wobj_W = c.cell.T_base_wobj.inverse();
  for (size_t i = 0; i < c.job.requests.size(); ++i)
    refs.push_back({c.job.requests[i].id, T_wobj_W * nominalHole(c, i).translation() * 1e3});
  return refs;
}

void noteMatch(VerifyResult& r) {
  for (const int k : r.match.unknown) {
    const postproc::MeasuredHole& m = r.measured.holes[static_cast<size_t>(k)];
    r.notes.push_back(r.measured.path + ":" + std::to_string(m.line) + ": measured hole " + m.id +
                      " is not a hole of the program: ignored");
  }
  for (const int i : r.match.unmeasured) {
    r.notes.push_back("program hole " +
                      r.prediction.context.job.requests[static_cast<size_t>(i)].id +
                      " was not measured");
  }
}

double uMeasurement(const postproc::MeasuredHole& m, const VerifyJob& job) {
  return (m.u_um ? *m.u_um : job.u_measurement_um) * 1e-6;
}

/// Measured position of hole i in the base frame (registration not removed).
Vec3 measuredW(const VerifyResult& r, int k) {
  return r.prediction.context.cell.T_base_wobj *
         (r.measured.holes[static_cast<size_t>(k)].p_mm * 1e-3);
}

/// The holes to verify: measured and predicted; the measured but unpredicted ones are failures.
void selectHoles(VerifyResult& r) {
  const PredictionContext& c = r.prediction.context;
  for (size_t i = 0; i < r.prediction.holes.size(); ++i) {
    const int k = r.match.measured_of_program[i];
    if (k < 0) continue;
    const HolePrediction& h = r.prediction.holes[i];
    if (h.status != HoleStatus::kOk) {
      r.failed.push_back(holeWhere(h.id, c.job.requests[i].line, r.program_path) + ": " +
                         verdictAndReason(h.verdict, h.reason));
      continue;
    }
    r.request_of.push_back(static_cast<int>(i));
    r.measured_of.push_back(k);
  }
}

/// A measured hole farther than this from its nominal position is not a drilling deviation.
constexpr double kMaxMeasuredDeviation = 25e-3;  // m

/// Refuses a measured hole that lies farther from its nominal hole than any drilling deviation
/// (swapped columns, another frame, metres for mm, another hole's id) before it reaches the
/// statistics or the identification.
void checkPlausibleDeviations(const VerifyResult& r) {
  const PredictionContext& c = r.prediction.context;
  for (size_t n = 0; n < r.request_of.size(); ++n) {
    const auto i = static_cast<size_t>(r.request_of[n]);
    const postproc::MeasuredHole& m = r.measured.holes[static_cast<size_t>(r.measured_of[n])];
    const double d = (measuredW(r, r.measured_of[n]) - nominalHole(c, i).translation()).norm();
    if (d <= kMaxMeasuredDeviation) continue;
    throw InputError(
        r.measured.path, m.line,
        "measured hole " + m.id + " lies " + numberText(d * 1e3, 4) +
            " mm from its nominal position (" +
            holeWhere(r.prediction.holes[i].id, c.job.requests[i].line, r.program_path) +
            "), more than any drilling deviation (25 mm); hint: check the column "
            "order, the frame (workobject, mm) and the hole ids");
  }
}

void identify(VerifyResult& r, const VerifyJob& job) {
  const PredictionContext& c = r.prediction.context;
  std::vector<IdentificationHole> holes;
  for (size_t n = 0; n < r.request_of.size(); ++n) {
    const auto i = static_cast<size_t>(r.request_of[n]);
    const HolePrediction& p = r.prediction.holes[i];
    IdentificationHole h;
    h.id = p.id;
    h.theta_cmd = p.joints;
    h.T_W_hole = nominalHole(c, i);
    h.diameter = c.job.requests[i].diameter;
    h.p_W_measured = measuredW(r, r.measured_of[n]);
    h.sigma = residualSigma(
        p, uMeasurement(r.measured.holes[static_cast<size_t>(r.measured_of[n])], job));
    holes.push_back(h);
  }
  IdentificationOptions o;
  o.compliance_prior_rel = compliancePriorSigma(c.robot.card);
  o.registration = r.registration;
  o.T_W_wobj = c.cell.T_base_wobj;
  if (job.identify_tool) o.tool = c.tool;
  r.identification = identifyStiffness(c.model, holes, o);
  for (const Eigen::Vector2d& e : r.identification->residuals)
    r.residual_identified.push_back(e.norm());
}

void verifyHoles(VerifyResult& r, const VerifyJob& job) {
  const PredictionContext& c = r.prediction.context;
  for (size_t n = 0; n < r.request_of.size(); ++n) {
    const auto i = static_cast<size_t>(r.request_of[n]);
    Vec3 p = measuredW(r, r.measured_of[n]);
    if (r.identification && r.registration != Registration::kNone)
      p = r.identification->registration.unregister(c.cell.T_base_wobj, p);
    const double u = uMeasurement(r.measured.holes[static_cast<size_t>(r.measured_of[n])], job);
    r.nominal.push_back(nominalHole(c, i));
    r.holes.push_back(verifyHole(verificationInput(r.prediction.holes[i], r.nominal.back(), p, u)));
  }
  r.summary = summarizeVerification(r.holes, c.cell.T_base_wobj.linear());
}

// ---------------------------------------------------------------- JSON

Json um(double m, int decimals = 3) { return Json::number(m * 1e6, decimals); }

Json vecUm(const Eigen::Ref<const Eigen::VectorXd>& v, double scale = 1e6, int decimals = 3) {
  return Json::vector(v * scale, decimals);
}

Json statsJson(const MagnitudeStats& s) {
  Json j = Json::object();
  j.set("rms", um(s.rms));
  j.set("mean", um(s.mean));
  j.set("max", um(s.max));
  return j;
}

Json registrationJson(const VerifyResult& r) {
  Json j = Json::object();
  j.set("kind", Json::str(registrationName(r.registration)));
  if (!r.identification || r.registration == Registration::kNone) return j;
  const RegistrationEstimate& g = r.identification->registration;
  j.set("frame", Json::str("workobject"));
  j.set("translation_um", vecUm(g.translation));
  j.set("translation_sigma_um", vecUm(g.translation_sigma));
  if (r.registration == Registration::kRigid) {
    j.set("rotation_urad", vecUm(g.rotation));
    j.set("rotation_sigma_urad", vecUm(g.rotation_sigma));
  }
  return j;
}

Json summaryJsonOf(const VerificationSummary& s) {
  Json j = Json::object();
  j.set("holes", Json::integer(s.holes));
  j.set("measured_um", statsJson(s.measured));
  j.set("predicted_um", statsJson(s.predicted));
  j.set("residual_um", statsJson(s.residual));
  j.set("explained", Json::number(s.explained, 4));
  j.set("inside", Json::integer(s.inside));
  j.set("coverage", Json::number(s.coverage, 4));
  // A correlation is undefined (NaN) with fewer than two holes or no spread along an axis: the
  // key is then left out (JSON has no NaN).
  if (s.correlation.allFinite())
    j.set("correlation_workobject_xyz", Json::vector(s.correlation, 4));
  Json d = Json::object();
  d.set("conformance-proven", Json::integer(s.conformance_proven));
  d.set("non-conformance-proven", Json::integer(s.nonconformance_proven));
  d.set("no-decision", Json::integer(s.no_decision));
  j.set("measured_decisions", d);
  return j;
}

Json parameterJson(const IdentifiedParameter& q) {
  Json j = Json::object();
  j.set("name", Json::str(q.name));
  j.set("unit", Json::str(q.unit));
  j.set("prior", Json::number(q.prior, -1));
  j.set("prior_sigma", Json::number(q.prior_sigma, -1));
  j.set("value", Json::number(q.value, -1));
  j.set("sigma", Json::number(q.sigma, -1));
  j.set("ratio", Json::number(q.ratio, 4));
  j.set("identifiable", Json::boolean(q.identifiable));
  return j;
}

Json jointsJson(const VerifyResult& r) {
  const IdentificationResult& id = *r.identification;
  const RobotCard& card = r.prediction.context.robot.card;
  Json a = Json::array();
  for (int j = 0; j < 6; ++j) {
    Json o = Json::object();
    o.set("joint", Json::integer(j + 1));
    o.set("k_card", Json::number(card.joints[static_cast<size_t>(j)].stiffness, -1));
    o.set("k", Json::number(id.compliance.k[j], 6));
    o.set("k_sigma", Json::number(id.k_sigma[j], 6));
    o.set("identified", Json::boolean(id.joint_identified[static_cast<size_t>(j)]));
    a.push(o);
  }
  return a;
}

Json covarianceJson(const Eigen::MatrixXd& P) {
  Json rows = Json::array();
  for (Eigen::Index i = 0; i < P.rows(); ++i) rows.push(Json::vector(P.row(i).transpose(), -1));
  return rows;
}

Json identificationJson(const VerifyResult& r) {
  const IdentificationResult& id = *r.identification;
  Json j = Json::object();
  j.set("converged", Json::boolean(id.converged));
  j.set("iterations", Json::integer(id.iterations));
  j.set("message", Json::str(id.message));
  j.set("holes", Json::integer(id.holes));
  // undefined (no column the data can see, or no Jacobian): the key is left out, never inf
  if (std::isfinite(id.condition_number))
    j.set("condition_number", Json::number(id.condition_number, -1));
  j.set("rms_prior_um", um(id.rms_prior));
  j.set("rms_final_um", um(id.rms_final));
  Json ps = Json::array();
  Json fixed = Json::array();
  for (const IdentifiedParameter& q : id.parameters) {
    ps.push(parameterJson(q));
    if (!q.identifiable) fixed.push(Json::str(q.name));
  }
  j.set("parameters", ps);
  j.set("not_identifiable", fixed);
  j.set("joints", jointsJson(r));
  j.set("covariance", covarianceJson(id.covariance));
  return j;
}

Json holeJsonOf(const VerifyResult& r, size_t n) {
  const HoleVerification& h = r.holes[n];
  const HoleRequest& q = r.prediction.context.job.requests[static_cast<size_t>(r.request_of[n])];
  Json j = Json::object();
  j.set("id", Json::str(h.id));
  j.set("line", Json::integer(q.line));
  j.set("measured_line",
        Json::integer(r.measured.holes[static_cast<size_t>(r.measured_of[n])].line));
  j.set("measured_um", vecUm(h.e_meas));
  j.set("measured_norm_um", um(h.e_meas_norm));
  j.set("measured_along_um", um(h.e_along));
  j.set("predicted_um", vecUm(h.d_pred));
  j.set("predicted_norm_um", um(h.d_pred_norm));
  j.set("residual_um", vecUm(h.r));
  j.set("residual_norm_um", um(h.r_norm));
  if (!r.residual_identified.empty()) j.set("residual_identified_um", um(r.residual_identified[n]));
  j.set("measured_base_um", vecUm(h.e_meas_W));
  j.set("predicted_base_um", vecUm(h.d_pred_W));
  j.set("U_work_um", um(h.U_work));
  j.set("U_region_um", um(h.U_region));
  j.set("inside", Json::boolean(h.inside));
  j.set("U_meas_um", um(h.U_meas));
  j.set("tolerance_mm", Json::number(h.tolerance * 1e3, 4));
  j.set("decision", Json::str(measuredDecisionName(h.decision)));
  return j;
}

Json strings(const std::vector<std::string>& v) {
  Json a = Json::array();
  for (const auto& s : v) a.push(Json::str(s));
  return a;
}

}  // namespace

std::string holeWhere(const std::string& id, int line, const std::string& program) {
  return line > 0 ? "hole " + id + " (" + program + ":" + std::to_string(line) + ")" : "hole " + id;
}

VerifyResult verifyJob(const std::string& cell_path, const std::string& program_path,
                       const VerifyJob& job, const ProgressFn& progress) {
  if (job.measured.empty()) throw UsageError("give the measured-hole file");
  if (!(job.u_measurement_um > 0)) throw UsageError("the measurement uncertainty must be > 0 µm");
  VerifyResult r;
  r.cell_path = cell_path;
  r.program_path = program_path;
  r.registration = job.registration;
  r.calibrate = job.calibrate;
  r.prediction = predictJob(cell_path, program_path, job.job, progress);
  r.measured = postproc::readMeasured(job.measured);
  r.match = postproc::matchMeasured(r.measured, programRefs(r.prediction.context));
  r.notes = r.prediction.context.job.notes;
  noteMatch(r);
  selectHoles(r);
  if (r.request_of.empty())
    throw InputError(job.measured, 0, "no measured hole of the program could be predicted");
  checkPlausibleDeviations(r);
  if (job.calibrate || job.identify_tool || job.registration != Registration::kNone)
    identify(r, job);
  verifyHoles(r, job);
  return r;
}

Json verifyJson(const VerifyResult& r) {
  const PredictionContext& c = r.prediction.context;
  Json root = Json::object();
  root.set("roprec", Json::str(version()));
  root.set("robot", Json::str(c.robot.card.name));
  root.set("cell", Json::str(c.cell.name));
  root.set("program", Json::str(baseName(r.program_path)));
  Json m = Json::object();
  m.set("file", Json::str(baseName(r.measured.path)));
  m.set("format", Json::str(postproc::measuredFormatName(r.measured.format)));
  m.set("holes", Json::integer(static_cast<std::int64_t>(r.measured.holes.size())));
  m.set("matched", Json::integer(r.match.matched));
  m.set("frame", Json::str("workobject"));
  root.set("measured", m);
  root.set("registration", registrationJson(r));
  root.set("summary", summaryJsonOf(r.summary));
  if (r.identification) root.set("identification", identificationJson(r));
  Json hs = Json::array();
  for (size_t n = 0; n < r.holes.size(); ++n) hs.push(holeJsonOf(r, n));
  root.set("holes", hs);
  root.set("failed", strings(r.failed));
  root.set("notes", strings(r.notes));
  return root;
}

Json verifySummaryJson(const VerifyResult& r, const std::vector<std::string>& written) {
  const VerificationSummary& s = r.summary;
  Json j = Json::object();
  j.set("holes", Json::integer(s.holes));
  j.set("matched", Json::integer(r.match.matched));
  j.set("failed", Json::integer(static_cast<std::int64_t>(r.failed.size())));
  j.set("rms_measured_um", um(s.measured.rms));
  j.set("rms_predicted_um", um(s.predicted.rms));
  j.set("rms_residual_um", um(s.residual.rms));
  j.set("explained", Json::number(s.explained, 4));
  j.set("coverage", Json::number(s.coverage, 4));
  j.set("registration", registrationJson(r));
  if (r.identification) {
    const IdentificationResult& id = *r.identification;
    Json o = Json::object();
    o.set("converged", Json::boolean(id.converged));
    if (std::isfinite(id.condition_number))
      o.set("condition_number", Json::number(id.condition_number, -1));
    o.set("rms_prior_um", um(id.rms_prior));
    o.set("rms_final_um", um(id.rms_final));
    o.set("joints", jointsJson(r));
    j.set("identification", o);
  }
  j.set("written", strings(written));
  return j;
}

std::string calibratedCardText(const VerifyResult& r, const std::string& measured_file_name,
                               const std::string& card_out_path) {
  if (!r.identification) throw UsageError("no identification: ask for calibration");
  const RobotCard& card = r.prediction.context.robot.card;
  std::string text =
      updateCardStiffness(readFileBytes(card.file), card.file, cardUpdates(*r.identification),
                          r.identification->holes, measured_file_name);
  if (card_out_path.empty()) return text;
  const fs::path urdf(card.urdf_path);
  const fs::path out_dir = fs::absolute(fs::path(card_out_path)).parent_path();
  if (fs::exists(out_dir / urdf.filename())) return text;
  const std::string attr = "urdf=\"" + urdf.filename().string() + "\"";
  const size_t at = text.find(attr);
  if (at == std::string::npos) return text;
  const std::string rel =
      fs::absolute(urdf).lexically_normal().lexically_relative(out_dir).string();
  return text.replace(at, attr.size(), "urdf=\"" + rel + "\"");
}

}  // namespace roprec::api
