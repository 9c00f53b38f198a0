#include "plugin/api/verify.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <regex>

#include "compensator/precision/card_writer.hpp"
#include "compensator/support/atomic_file.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"
#include "compensator/support/rotation.hpp"
#include "compensator/support/xml_escape.hpp"

namespace roprec::api {
namespace {

namespace fs = std::filesystem;

std::string baseName(const std::string& path) { return fs::path(path).filename().string(); }

/// The nominal hole of request i: the hole list's when one was matched (its point and axis; the
/// program's rotation about the axis when the axes agree), else the program's drill point; on
/// the part where the cell's <part_registration> found it (partMotion).
Pose nominalHole(const PredictionContext& c, size_t i);

Pose nominalHoleOfJob(const PredictionContext& c, size_t i) {
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

Pose nominalHole(const PredictionContext& c, size_t i) {
  if (!c.cell.part_registration) return nominalHoleOfJob(c, i);
  return partMotion(c.cell) * nominalHoleOfJob(c, i);
}

std::vector<postproc::ProgramHoleRef> programRefs(const PredictionContext& c) {
  std::vector<postproc::ProgramHoleRef> refs;
  const Pose T_wobj_W = c.cell.T_base_wobj.inverse();
  for (size_t i = 0; i < c.job.requests.size(); ++i)
    refs.push_back({c.job.requests[i].id, T_wobj_W * nominalHoleOfJob(c, i).translation() * 1e3});
  return refs;
}

/// The job options of verify's prediction: the program as it was drilled (the nominal holes and
/// the measured positions are moved with the part here, nominalHole and measuredW).
JobOptions asDrilled(JobOptions o) {
  o.registered_part = false;
  return o;
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

/// Measured position of hole i in the base frame (registration not removed): the part's
/// coordinates through the workobject, on the part where the cell's <part_registration> found it.
Vec3 measuredW(const VerifyResult& r, int k) {
  const CellSpec& cell = r.prediction.context.cell;
  const Vec3 p = cell.T_base_wobj * (r.measured.holes[static_cast<size_t>(k)].p_mm * 1e-3);
  return cell.part_registration ? Vec3(partMotion(cell) * p) : p;
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

/// The χ² check and the held-out validation of a calibration; the card is refused when the
/// validation finds it no better than the original card.
/// Whether the held-out validation can run (a note when not).
bool canValidate(VerifyResult& r, const VerifyJob& job) {
  const int n = static_cast<int>(r.observations.size());
  if (job.folds <= 0) {
    r.notes.push_back("no held-out validation (--folds 0): the card is written unchecked");
    return false;
  }
  if (n < 2 * job.folds) {
    r.notes.push_back("no held-out validation: " + std::to_string(n) +
                      " measured observations are fewer than 2 per fold for " +
                      std::to_string(job.folds) + " folds");
    return false;
  }
  return true;
}

/// --identify all: the geometry is identified when it is observable enough to help — when its
/// k-fold held-out residual is below the compliances-alone one (a small test part cannot hold
/// 42 more parameters: the priors then shape them, and the held-out residual says so). Returns
/// the options to identify with and their validation.
std::pair<IdentificationOptions, HeldOutValidation> chooseParameters(
    VerifyResult& r, const VerifyJob& job, const IdentificationOptions& all) {
  const PredictionModel& m = r.prediction.context.model;
  const HeldOutValidation with = crossValidate(m, r.observations, all, job.folds);
  if (job.identify != IdentifySet::kAll || !all.geometry) return {all, with};
  IdentificationOptions stiffness = all;
  stiffness.geometry = false;
  const HeldOutValidation without = crossValidate(m, r.observations, stiffness, job.folds);
  if (with.rms_calibrated < without.rms_calibrated) return {all, with};
  r.notes.push_back("the geometry is not identified: with it the held-out residual is " +
                    numberText(with.rms_calibrated * 1e6, 4) +
                    " µm RMS, with the joint "
                    "compliances alone " +
                    numberText(without.rms_calibrated * 1e6, 4) + " µm (" +
                    std::to_string(job.folds) +
                    "-fold cross-validation): these "
                    "measurements do not hold the geometry; measure more poses, directions "
                    "or a larger region (roprec plan-test)");
  return {stiffness, without};
}

/// The identification with its χ² check and held-out validation; the card is refused when the
/// validation finds it no better than the original card.
void calibrate(VerifyResult& r, const VerifyJob& job, IdentificationOptions o) {
  if (canValidate(r, job)) {
    auto [chosen, validation] = chooseParameters(r, job, o);
    o = chosen;
    r.validation = validation;
  }
  r.identification = identifyStiffness(r.prediction.context.model, r.observations, o);
  r.fit_check = checkFit(*r.identification, r.observations);
  if (r.validation && !r.validation->better) {
    r.card_refused = "its held-out residual (" + numberText(r.validation->rms_calibrated * 1e6, 4) +
                     " µm RMS, " + std::to_string(job.folds) +
                     "-fold cross-validation) is not below the original card's (" +
                     numberText(r.validation->rms_original * 1e6, 4) + " µm)";
  }
}

/// The identification's hole frame: the nominal hole, its in-plane axes ⊥ the measured hole axis
/// when the file has one (the real drilled axis: the position ⊥ it is what the CMM measured
/// meaningfully); the measured axis is oriented like the nominal drilling direction.
Pose measuredAxisFrame(const VerifyResult& r, const Pose& nominal, int k) {
  const postproc::MeasuredHole& m = r.measured.holes[static_cast<size_t>(k)];
  if (!m.axis) return nominal;
  Vec3 a = r.prediction.context.cell.T_base_wobj.linear() * m.axis->normalized();
  if (a.dot(nominal.linear().col(2)) < 0) a = -a;
  Pose T = nominal;
  T.linear() = holeFrame(a);
  return T;
}

/// The commanded joints of the program's target a pose row names (its j1..j6 left empty): those
/// the prediction of the program found for that target.
Vec6 programTargetJoints(const VerifyResult& r, const postproc::MeasuredPose& q) {
  const std::vector<HolePrediction>& holes = r.prediction.holes;
  if (r.program_path.empty())
    throw InputError(r.poses.path, q.line,
                     "pose " + q.id +
                         " has no joints (j1..j6 empty): give them, or the PROGRAM whose target "
                         "it names");
  for (size_t i = 0; i < holes.size(); ++i) {
    if (holes[i].id != q.id) continue;
    if (holes[i].status != HoleStatus::kOk)
      throw InputError(
          r.poses.path, q.line,
          "pose " + q.id + " names " +
              holeWhere(holes[i].id, r.prediction.context.job.requests[i].line, r.program_path) +
              ", which has no predicted joints: " +
              verdictAndReason(holes[i].verdict, holes[i].reason));
    return holes[i].joints;
  }
  throw InputError(r.poses.path, q.line,
                   "pose " + q.id + " has no joints (j1..j6 empty) and names no target of " +
                       r.program_path +
                       "; hint: give j1..j6, or the id of a target of the program");
}

/// A measured pose as an observation: the commanded joints from the controller's convention, the
/// measured TCP (and its orientation, when the row has one) in the base frame, gravity with the
/// row's payload and applied wrench.
IdentificationHole poseObservation(const VerifyResult& r, const postproc::MeasuredPose& q,
                                   const VerifyJob& job) {
  const PredictionContext& c = r.prediction.context;
  IdentificationHole h;
  h.id = q.id;
  h.point = true;
  h.theta_cmd = q.program_target ? programTargetJoints(r, q)
                                 : fromControllerJoints(c.robot.card, q.joints_deg * kDeg);
  h.T_W_hole = Pose::Identity();
  h.T_W_hole.linear() = c.cell.T_base_wobj.linear();  // residual axes: the workobject's
  h.p_W_measured = c.cell.T_base_wobj * (q.p_mm * 1e-3);
  h.sigma = (q.u_um ? *q.u_um : job.u_measurement_um) * 1e-6;
  if (q.rpy_deg) {
    const Vec3 rpy = *q.rpy_deg * kDeg;
    h.R_W_measured = c.cell.T_base_wobj.linear() * rotationFromRpy(rpy.x(), rpy.y(), rpy.z());
    h.sigma_rotation = (q.u_rot_urad ? *q.u_rot_urad : job.u_rotation_urad) * 1e-6;
  }
  nc::Loads loads = processLoads(c.model, nullptr);
  if (q.force_n) loads.tcp = nc::Wrench{*q.force_n, q.torque_nm};
  h.loads = loads;
  if (q.payload_kg && *q.payload_kg > 0) {
    nc::ToolAttachment t = c.tool;
    const double m = t.mass + *q.payload_kg;
    t.com = (t.mass * t.com + *q.payload_kg * q.payload_com_mm * 1e-3) / m;
    t.mass = m;
    h.tool = t;
  }
  return h;
}

/// The hole's own process in the observation: its drill, diameter, feed and speed, and the
/// drill's TCP and mass when it has a <tcp> of its own (the model is rebuilt with that tool).
void ownProcess(const PredictionContext& c, const HoleRequest& q, IdentificationHole& h) {
  h.diameter = q.diameter;
  h.drill = q.drill;
  h.feed = q.feed;
  h.spindle_rpm = q.spindle_rpm;
  if (&modelFor(c.model, q) == &c.model) return;
  const std::vector<std::optional<DrillTool>> tools = drillToolsOf(c.cell, c.robot.card);
  h.tool = tools[static_cast<size_t>(std::max(q.drill, 0))]->tool;
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
    h.T_W_hole = measuredAxisFrame(r, nominalHole(c, i), r.measured_of[n]);
    ownProcess(c, c.job.requests[i], h);
    h.p_W_measured = measuredW(r, r.measured_of[n]);
    h.sigma = residualSigma(
        p, uMeasurement(r.measured.holes[static_cast<size_t>(r.measured_of[n])], job));
    holes.push_back(h);
  }
  for (const postproc::MeasuredPose& q : r.poses.poses) holes.push_back(poseObservation(r, q, job));
  IdentificationOptions o;
  o.identify = job.identify;
  o.geometry = job.calibrate && job.identify != IdentifySet::kStiffness;
  o.compliance_prior_rel = compliancePriorSigma(c.robot.card);
  o.registration = r.registration;
  o.T_W_wobj = c.cell.T_base_wobj;
  if (job.identify_tool) o.tool = c.tool;
  r.observations = holes;
  if (job.calibrate)
    calibrate(r, job, o);
  else
    r.identification = identifyStiffness(c.model, holes, o);
  for (const Eigen::VectorXd& e : r.identification->residuals)
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

}  // namespace

std::string holeWhere(const std::string& id, int line, const std::string& program) {
  return line > 0 ? "hole " + id + " (" + program + ":" + std::to_string(line) + ")" : "hole " + id;
}

namespace {

/// The drilled part of a job: the program predicted, the measured holes read and matched.
void readHoles(VerifyResult& r, const std::string& cell_path, const std::string& program_path,
               const VerifyJob& job, const ProgressFn& progress) {
  if (job.measured.empty()) throw UsageError("give the measured-hole file with the program");
  r.prediction = predictJob(cell_path, program_path, asDrilled(job.job), progress);
  r.measured = postproc::readMeasured(job.measured);
  r.match = postproc::matchMeasured(r.measured, programRefs(r.prediction.context));
  r.notes = r.prediction.context.job.notes;
  noteMatch(r);
  selectHoles(r);
  if (r.request_of.empty())
    throw InputError(job.measured, 0, "no measured hole of the program could be predicted");
  checkPlausibleDeviations(r);
}

}  // namespace

std::string calibrationDate(const std::string& date, const std::string& measured_file) {
  if (!date.empty()) {
    int y = 0, m = 0, d = 0;
    char tail = 0;
    if (!std::regex_match(date, std::regex("[0-9]{4}-[0-9]{2}-[0-9]{2}")) ||
        std::sscanf(date.c_str(), "%d-%d-%d%c", &y, &m, &d, &tail) != 3 || m < 1 || m > 12 ||
        d < 1 || d > 31)
      throw UsageError("--date must be YYYY-MM-DD, not '" + date + "'");
    return date;
  }
  std::time_t t = 0;
  const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
  if (epoch != nullptr && *epoch != '\0') {
    if (!std::regex_match(epoch, std::regex("[0-9]{1,12}")))
      throw UsageError(std::string("SOURCE_DATE_EPOCH must be whole seconds, not '") + epoch + "'");
    t = static_cast<std::time_t>(std::stoll(epoch));
  } else {
    const auto ft = fs::last_write_time(platform::fromUtf8(measured_file));
    t = std::chrono::system_clock::to_time_t(std::chrono::file_clock::to_sys(ft));
  }
  // the UTC calendar day (std::chrono: no gmtime_r, which Windows lacks)
  const std::chrono::year_month_day day{
      std::chrono::floor<std::chrono::days>(std::chrono::system_clock::from_time_t(t))};
  char buf[48];
  std::snprintf(buf, sizeof buf, "%04d-%02u-%02u", static_cast<int>(day.year()),
                static_cast<unsigned>(day.month()), static_cast<unsigned>(day.day()));
  return buf;
}

VerifyResult verifyJob(const std::string& cell_path, const std::string& program_path,
                       const VerifyJob& job, const ProgressFn& progress) {
  if (job.measured.empty() && job.poses.empty())
    throw UsageError("give the measured-hole file (or a pose file)");
  if (!(job.u_measurement_um > 0)) throw UsageError("the measurement uncertainty must be > 0 µm");
  VerifyResult r;
  r.cell_path = cell_path;
  r.program_path = program_path;
  r.registration = job.registration;
  r.calibrate = job.calibrate;
  if (job.calibrate)
    r.date = calibrationDate(job.date, job.measured.empty() ? job.poses : job.measured);
  if (!program_path.empty() && job.measured.empty()) {  // poses naming the program's targets
    r.prediction = predictJob(cell_path, program_path, asDrilled(job.job), progress);
    r.notes = r.prediction.context.job.notes;
  } else if (!program_path.empty()) {
    readHoles(r, cell_path, program_path, job, progress);
  } else {
    if (!job.measured.empty())
      throw UsageError("measured holes need the PROGRAM that drilled them");
    r.prediction.context = loadPredictionContext(cell_path, "", std::nullopt, "", 0.5, false);
  }
  if (!job.poses.empty()) r.poses = postproc::readMeasuredPoses(job.poses);
  if (job.calibrate || job.identify_tool || job.registration != Registration::kNone ||
      !r.poses.poses.empty())
    identify(r, job);
  verifyHoles(r, job);
  return r;
}

namespace {

/// The calibration's model error floor (modelErrorFloor): from the held-out residuals when the
/// calibration was cross-validated, else from the fit's own (dof-inflated).
double modelErrorFloor(const VerifyResult& r) {
  if (r.validation) return roprec::modelErrorFloor(r.validation->calibrated, r.observations);
  const IdentificationResult& id = *r.identification;
  std::vector<double> norms;
  for (const Eigen::VectorXd& e : id.residuals) norms.push_back(e.norm());
  const double inflation = id.dof > 0 ? static_cast<double>(id.equations) / id.dof : 1.0;
  return roprec::modelErrorFloor(norms, r.observations, inflation);
}

}  // namespace

std::string calibratedCardText(const VerifyResult& r, const std::string& measured_file_name,
                               const std::string& card_out_path) {
  if (!r.identification) throw UsageError("no identification: ask for calibration");
  const RobotCard& card = r.prediction.context.robot.card;
  std::string text =
      updateCardStiffness(readFileBytes(card.file), card.file, cardUpdates(*r.identification),
                          r.identification->holes, measured_file_name);
  if (r.identification->geometry) {
    GeometryCalibration g = *r.identification->geometry;
    g.source =
        "identified: " + std::to_string(r.identification->holes) + " observations from " +
        measured_file_name + " by roprec verify (" +
        (r.fit_check
             ? "fit residual " + numberText(r.fit_check->rms_normalized, 3) + " σ" +
                   (r.validation ? ", held-out " +
                                       numberText(r.validation->rms_calibrated * 1e6, 3) + " µm RMS"
                                 : std::string())
             : std::string("unchecked")) +
        ")";
    g.date = r.date;
    g.residual_rms = r.identification->rms_final;
    g.model_error = modelErrorFloor(r);
    g.measurements = r.identification->holes;
    std::array<std::string, 6> names;
    for (size_t i = 0; i < 6; ++i) names[i] = card.joints[i].name;
    text = replaceCardCalibration(text, card.file, calibrationXml(g, names, "  "));
  }
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

namespace roprec::api {
namespace {

/// [begin, end) of the first start tag `<name …>` outside comments, or nullopt.
std::optional<std::pair<size_t, size_t>> startTag(const std::string& text,
                                                  const std::string& name) {
  size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 4, "<!--") == 0) {
      at = text.find("-->", at);
      if (at == std::string::npos) return std::nullopt;
      continue;
    }
    const size_t after = at + 1 + name.size();
    if (text.compare(at + 1, name.size(), name) == 0 && after < text.size() &&
        (std::isspace(static_cast<unsigned char>(text[after])) || text[after] == '/' ||
         text[after] == '>')) {
      const size_t end = text.find('>', after);
      if (end == std::string::npos) return std::nullopt;
      return std::make_pair(at, end + 1);
    }
    ++at;
  }
  return std::nullopt;
}

int lineAt(const std::string& text, size_t at) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

/// The tag with attribute `name` set to `value` (replaced when present, else added).
std::string withAttribute(std::string tag, const std::string& name, const std::string& value) {
  const std::regex re("(\\s)" + name + "\\s*=\\s*(\"[^\"]*\"|'[^']*')");
  std::smatch m;
  if (std::regex_search(tag, m, re))
    return tag.replace(static_cast<size_t>(m.position(0)), static_cast<size_t>(m.length(0)),
                       m.str(1) + name + "=\"" + value + "\"");
  const size_t close = tag.size() - (tag.size() >= 2 && tag[tag.size() - 2] == '/' ? 2 : 1);
  return tag.insert(close, " " + name + "=\"" + value + "\"");
}

std::string withoutAttribute(std::string tag, const std::string& name) {
  return std::regex_replace(tag, std::regex("\\s" + name + "\\s*=\\s*(\"[^\"]*\"|'[^']*')"), "");
}

std::optional<std::string> attribute(const std::string& tag, const std::string& name) {
  const std::regex re("\\s" + name + "\\s*=\\s*(\"([^\"]*)\"|'([^']*)')");
  std::smatch m;
  if (!std::regex_search(tag, m, re)) return std::nullopt;
  return m[2].matched ? m.str(2) : m.str(3);
}

/// Fixed decimals in the "C" locale, without a negative zero.
std::string fixedText(double v, int decimals) {
  return cFixed(std::abs(v) < 0.5 * std::pow(10.0, -decimals) ? 0.0 : v, decimals);
}

std::string triple(const Vec3& v, int decimals) {
  return fixedText(v.x(), decimals) + " " + fixedText(v.y(), decimals) + " " +
         fixedText(v.z(), decimals);
}

std::string relativePath(const std::string& target, const std::string& from_file) {
  const fs::path dir = fs::absolute(fs::path(from_file)).parent_path();
  return fs::absolute(fs::path(target)).lexically_normal().lexically_relative(dir).string();
}

/// The `<robot>` tag for the new cell: the new card, else the old reference re-rooted.
std::string robotTag(const std::string& tag, const VerifyResult& r, const std::string& cell_out,
                     const std::string& card_path) {
  if (!card_path.empty())
    return withAttribute(withoutAttribute(tag, "ref"), "file", relativePath(card_path, cell_out));
  if (const auto f = attribute(tag, "file")) {
    const fs::path old = fs::path(*f).is_absolute()
                             ? fs::path(*f)
                             : fs::path(r.cell_path).parent_path() / fs::path(*f);
    return withAttribute(tag, "file", relativePath(old.string(), cell_out));
  }
  return tag;
}

/// The cell's <part_registration> composed with the one estimated (verify measured the part
/// through the cell's registration): F = F_cell · [R(ω), t], written in mm and mrad (rpy, URDF
/// order) with its source.
std::string partRegistrationTag(const VerifyResult& r) {
  const RegistrationEstimate& g = r.identification->registration;
  Pose F = Pose::Identity();
  F.linear() =
      Eigen::AngleAxisd(g.rotation.norm(),
                        g.rotation.norm() > 0 ? Vec3(g.rotation.normalized()) : Vec3::UnitZ())
          .toRotationMatrix();
  F.translation() = g.translation;
  const std::optional<Pose>& before = r.prediction.context.cell.part_registration;
  if (before) F = *before * F;
  const std::string source =
      std::string("roprec verify --register ") + registrationName(r.registration) + ": " +
      std::to_string(r.identification->holes) + " holes of " + baseName(r.measured.path) +
      (before ? ", on the cell's" : "") + (r.date.empty() ? std::string() : ", " + r.date);
  return "<part_registration xyz_mm=\"" + triple(F.translation() * 1e3, 4) + "\" rpy_mrad=\"" +
         triple(rpyFromRotation(F.linear()) * 1e3, 6) + "\" source=\"" + escapeXml(source, '"') +
         "\"/>";
}

}  // namespace

std::string calibratedCellText(const VerifyResult& r, const std::string& cell_out_path,
                               const std::string& card_path) {
  if (!r.identification) throw UsageError("no identification: ask for --register or --calibrate");
  std::string text = readFileBytes(r.cell_path);
  const auto robot = startTag(text, "robot");
  if (!robot || text[robot->second - 2] != '/')
    throw InputError(r.cell_path, robot ? lineAt(text, robot->first) : 0,
                     "the cell's <robot> element is not one empty-element tag <robot .../>: "
                     "cannot write the new cell; hint: write <robot ref|file=\"...\"/>");
  const std::string new_robot = robotTag(text.substr(robot->first, robot->second - robot->first), r,
                                         cell_out_path, card_path);
  text.replace(robot->first, robot->second - robot->first, new_robot);

  if (r.registration == Registration::kNone) return text;  // the part stays where the cell has it
  const std::string tag = partRegistrationTag(r);
  const auto old = startTag(text, "part_registration");
  if (old) {
    if (text[old->second - 2] != '/')
      throw InputError(r.cell_path, lineAt(text, old->first),
                       "the cell's <part_registration> element is not one empty-element tag: "
                       "cannot write the new cell");
    text.replace(old->first, old->second - old->first, tag);
    return text;
  }
  const auto wobj = startTag(text, "workobject");
  const size_t after = wobj ? wobj->second : text.find('>', text.find(new_robot)) + 1;
  const size_t tag_start = wobj ? wobj->first : text.find(new_robot);
  const size_t line_start = text.rfind('\n', tag_start);
  const std::string indent =
      text.substr(line_start == std::string::npos ? 0 : line_start + 1,
                  tag_start - (line_start == std::string::npos ? 0 : line_start + 1));
  text.insert(after, "\n" + indent + tag);
  return text;
}

}  // namespace roprec::api
