/// \file verify_json.cpp
/// The JSON texts of `roprec verify` (see verify_json.hpp).
#include "plugin/report/verify_json.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>

namespace roprec::api {
namespace {

std::string baseName(const std::string& path) {
  return std::filesystem::path(path).filename().string();
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

/// The χ² check and the held-out validation (calibrate only).
void setValidationJson(Json& j, const VerifyResult& r) {
  if (r.fit_check) {
    const FitCheck& f = *r.fit_check;
    Json o = Json::object();
    o.set("chi2", Json::number(f.chi2, -1));
    o.set("dof", Json::integer(f.dof));
    o.set("rms_normalized", Json::number(f.rms_normalized, 4));
    o.set("rms_limit", Json::number(f.rms_limit, 4));
    o.set("chi2_quantile_999", Json::number(f.chi2_999, -1));
    o.set("consistent", Json::boolean(f.consistent));
    Json b = Json::object();
    b.set("name", Json::str(f.best.name));
    b.set("value", Json::str(f.best.value));
    b.set("share", Json::number(f.best.share, 4));
    o.set("largest_unmodelled_effect", b);
    o.set("explanation", Json::str(f.explanation));
    j.set("fit_check", o);
  }
  if (r.validation) {
    const HeldOutValidation& v = *r.validation;
    Json o = Json::object();
    o.set("folds", Json::integer(v.folds));
    o.set("rms_calibrated_um", um(v.rms_calibrated));
    o.set("rms_original_um", um(v.rms_original));
    o.set("better", Json::boolean(v.better));
    j.set("validation", o);
  }
  if (r.calibrate) j.set("card_refused", Json::str(r.card_refused));
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
  // geometry only (the key is absent for a stiffness identification: outputs unchanged)
  if (id.geometry) {
    Json deps = Json::array();
    for (const std::string& d : id.dependencies) deps.push(Json::str(d));
    j.set("dependencies", deps);
  }
  j.set("joints", jointsJson(r));
  j.set("covariance", covarianceJson(id.covariance));
  setValidationJson(j, r);
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

/// The measured poses: file, count and per pose |measured − predicted| after identification.
Json posesJson(const VerifyResult& r) {
  Json j = Json::object();
  j.set("file", Json::str(baseName(r.poses.path)));
  j.set("count", Json::integer(static_cast<std::int64_t>(r.poses.poses.size())));
  j.set("frame", Json::str("workobject"));
  Json a = Json::array();
  const size_t first = r.observations.size() - r.poses.poses.size();
  for (size_t k = 0; k < r.poses.poses.size(); ++k) {
    Json o = Json::object();
    o.set("id", Json::str(r.poses.poses[k].id));
    o.set("line", Json::integer(r.poses.poses[k].line));
    if (r.identification)
      o.set("residual_identified_um", vecUm(r.identification->residuals[first + k]));
    // a measured orientation: its residual (the key is absent without one: outputs unchanged)
    if (r.identification && r.poses.poses[k].rpy_deg)
      o.set("rotation_residual_identified_urad",
            vecUm(r.identification->rotation_residuals[first + k]));
    a.push(o);
  }
  j.set("poses", a);
  return j;
}

Json strings(const std::vector<std::string>& v) {
  Json a = Json::array();
  for (const auto& s : v) a.push(Json::str(s));
  return a;
}

}  // namespace

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
  if (!r.poses.poses.empty()) root.set("poses", posesJson(r));
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
    setValidationJson(o, r);
    j.set("identification", o);
  }
  j.set("written", strings(written));
  return j;
}

}  // namespace roprec::api
