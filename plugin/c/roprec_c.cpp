/// \file roprec_c.cpp
/// The C ABI (plugin/c/roprec.h) over the host-facing job API (plugin/api/job.hpp): argument
/// checks, unit and layout conversion (mm/deg/row-major <-> SI/Eigen), and a guard that turns
/// every C++ exception into a status code and a copied message. No global mutable state.
#define ROPREC_C_BUILDING 1
#include "plugin/c/roprec.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <new>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compensator/precision/identification.hpp"
#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/job_options.hpp"
#include "plugin/api/plan_test.hpp"
#include "plugin/api/verify.hpp"
#include "plugin/c/host_common.hpp"
#include "plugin/report/plan_test_json.hpp"
#include "plugin/report/verify_json.hpp"

struct roprec_session {
  explicit roprec_session(const std::string& path) : cell_path(path), session(path) {}
  std::string cell_path;
  roprec::api::Session session;
};

/// The job options of roprec_predict_file_ex / roprec_compensate_file_ex (roprec_options_set).
struct roprec_options {
  roprec::api::CompensationJob job;  ///< job.job: the prediction options; mode, force
  /// roprec_verify_file_ex only: --write-cell, --poses, --identify, --folds, --date, --u-rot.
  std::string write_cell, poses, date;
  roprec::IdentifySet identify{roprec::IdentifySet::kAll};
  int folds{5};
  double u_rot_urad{roprec::api::VerifyJob{}.u_rotation_urad};
};

namespace {

namespace host = roprec::host;
using roprec::Pose;
using roprec::Vec6;

/// Copies `a` then `b` into err (truncated to err_len − 1 bytes without splitting a UTF-8
/// sequence; always NUL-terminated). Never allocates.
void copyError(char* err, size_t err_len, const char* a, const char* b = "") noexcept {
  if (err == nullptr || err_len == 0) return;
  size_t n = 0;
  bool truncated = false;
  for (const char* src : {a, b}) {
    for (; *src != '\0'; ++src) {
      if (n + 1 >= err_len) {
        truncated = true;
        break;
      }
      err[n++] = *src;
    }
  }
  if (truncated) {
    size_t k = 0;  // continuation bytes at the end
    while (k < n && (static_cast<unsigned char>(err[n - 1 - k]) & 0xC0) == 0x80) ++k;
    if (k < n) {
      const auto lead = static_cast<unsigned char>(err[n - 1 - k]);
      const size_t len = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
      if (len > 1 && k + 1 < len) n -= k + 1;  // the last sequence lost bytes: drop it
    }
  }
  err[n] = '\0';
}

/// The ROPREC_ERROR_* kind of the last call's error on this thread (roprec_error_kind).
thread_local int g_error_kind = ROPREC_ERROR_NONE;

/// An item failure (status 1) carrying its message.
struct ItemFailure {
  std::string message;
};

/// Runs `f` (returning a status) and maps every exception to a status with its text.
template <class F>
int guarded(char* err, size_t err_len, F&& f) noexcept {
  copyError(err, err_len, "");
  g_error_kind = ROPREC_ERROR_NONE;
  try {
    // The outputs of one call are written all or none (compensator/support/atomic_file.hpp):
    // committed when the call returns or reports failed items (whose outputs were complete),
    // removed on any error. Numbers are formatted locale-free whatever locale the host set.
    roprec::OutputSet outputs;
    const roprec::ScopedOutputSet scope(outputs);
    int status = ROPREC_OK;
    try {
      status = f();
    } catch (const ItemFailure&) {
      outputs.commit();
      throw;
    }
    outputs.commit();
    return status;
  } catch (const ItemFailure& e) {
    copyError(err, err_len, e.message.c_str());
    g_error_kind = ROPREC_ERROR_ITEM;
    return ROPREC_ITEM_FAILED;
  } catch (const roprec::InputError& e) {
    copyError(err, err_len, e.what());
    g_error_kind = ROPREC_ERROR_INPUT;
    return ROPREC_BAD_INPUT;
  } catch (const roprec::UsageError& e) {
    copyError(err, err_len, e.what());
    g_error_kind = ROPREC_ERROR_USAGE;
    return ROPREC_BAD_INPUT;
  } catch (const std::bad_alloc&) {
    copyError(err, err_len, "out of memory");
    g_error_kind = ROPREC_ERROR_MEMORY;
    return ROPREC_BAD_INPUT;
  } catch (const std::exception& e) {
    copyError(err, err_len, "internal error: ", e.what());
    g_error_kind = ROPREC_ERROR_INTERNAL;
    return ROPREC_BAD_INPUT;
  } catch (...) {
    copyError(err, err_len, "internal error (unknown exception)");
    g_error_kind = ROPREC_ERROR_INTERNAL;
    return ROPREC_BAD_INPUT;
  }
}

void require(const void* p, const char* name) {
  if (p == nullptr) throw roprec::UsageError(std::string(name) + " is NULL");
}

std::string pathArg(const char* p, const char* name) {
  require(p, name);
  if (*p == '\0') throw roprec::UsageError(std::string(name) + " is empty");
  return p;
}

/// NULL or "" -> "".
std::string optionalArg(const char* p) { return p == nullptr ? std::string() : std::string(p); }

/// Checks the (buffer, length) pair of an optional output text and empties the buffer.
void checkTextBuffer(char* buf, size_t len, const char* name) {
  if (buf == nullptr && len != 0)
    throw roprec::UsageError(std::string(name) + " is NULL but its length is not 0");
  if (buf != nullptr && len > 0) buf[0] = '\0';
}

/// UsageError unless `text` fits (with its NUL) into an optional buffer.
void checkFits(const std::string& text, const char* buf, size_t len, const char* name) {
  if (buf != nullptr && text.size() + 1 > len) {
    throw roprec::UsageError(std::string(name) + ": the buffer holds " + std::to_string(len) +
                             " bytes, " + std::to_string(text.size() + 1) +
                             " are needed; nothing was written");
  }
}

void copyText(const std::string& text, char* buf) {
  if (buf != nullptr) std::memcpy(buf, text.c_str(), text.size() + 1);
}

/// The common end of a compensation call: the summary must fit its buffer before anything is
/// written; then the corrected program and its extra outputs, then the summary is copied.
int writeCompensation(roprec::api::PredictionContext& context, const std::string& out,
                      const std::vector<std::pair<std::string, std::string>>& extra,
                      const std::string& summary, char* summary_json, size_t summary_len) {
  checkFits(summary, summary_json, summary_len, "summary_json");
  roprec::api::writeCompensatedProgram(context, out, extra);
  copyText(summary, summary_json);
  return ROPREC_OK;
}

/// The milling job of roprec_compensate_file(_ex): its files staged (committed with the call's
/// outputs), then the summary copied, or the failures and refused edits (nothing written).
int compensateMilling(const std::string& cell, const std::string& program, const std::string& out,
                      const std::string& targets, const roprec::api::CompensationJob& job,
                      char* summary, size_t summary_len) {
  roprec::api::MillingFilesJob files;
  files.cell = cell;
  files.program = program;
  files.out = out;
  if (!targets.empty()) files.targets = targets;
  files.force = job.force;
  files.threads = roprec::api::resolvedThreads(job.job.threads);
  const roprec::api::MillingFilesResult r = roprec::api::compensateMillingFiles(files);
  if (const std::string why = host::millingProblems(r); !why.empty()) throw ItemFailure{why};
  const std::string text = host::millingSummary(r).dump(0);
  checkFits(text, summary, summary_len, "summary_json");
  copyText(text, summary);
  return ROPREC_OK;
}

/// A pose as 16 numbers, row-major, mm (shortest round-trip text).
roprec::api::Json poseJson(const roprec::Pose& T) {
  double m[16];
  host::poseToRowMajorMm(T, m);
  return roprec::api::Json::vector(Eigen::Map<const Eigen::VectorXd>(m, 16));
}

/// The figures of roprec_predict_joints_json (the Python module's predict_joints keys).
roprec::api::Json jointPredictionJson(const roprec::api::Session::JointPrediction& p,
                                      const Vec6& q) {
  using roprec::api::Json;
  const roprec::HolePrediction& h = p.prediction;
  Vec6 deg;
  for (int i = 0; i < 6; ++i) deg[i] = q[i] / roprec::kDeg;
  Json o = Json::object();
  o.set("deviation_um", Json::vector(p.d_translation * 1e6));
  o.set("rotation_urad", Json::vector(p.d_rotation * 1e6));
  o.set("U_work_um", Json::number(p.U_work * 1e6));
  o.set("U_robot_um", Json::number(h.U_robot * 1e6));
  o.set("U_mach_um", Json::number(h.U_mach * 1e6));
  o.set("k", Json::number(h.k));
  o.set("work_deviation_um", Json::vector(h.d_work * 1e6));
  o.set("position_error_um", Json::number(h.position_error * 1e6));
  o.set("axis_tilt_urad", Json::number(h.axis_tilt * 1e6));
  o.set("tolerance_mm", Json::number(h.tolerance * 1e3));
  o.set("verdict", Json::str(roprec::verdictName(h.verdict)));
  o.set("config", Json::str(h.config));
  o.set("joints_deg", Json::vector(deg));
  o.set("process_force_N", Json::vector(h.force_base));
  return o;
}

/// The process a call used (roprec_*_hole_json's "process"; the Python module's process dict).
roprec::api::Json processUsedJson(const roprec::api::ProcessUsed& u) {
  using roprec::api::Json;
  Json o = Json::object();
  o.set("tool", Json::str(u.tool));
  o.set("drill", Json::str(u.drill));
  o.set("diameter_mm", Json::number(u.diameter * 1e3));
  o.set("depth_mm", Json::number(u.depth * 1e3));
  o.set("feed_mm_per_rev", Json::number(u.feed * 1e3));
  o.set("spindle_rpm", Json::number(u.spindle_rpm));
  o.set("from_cell", Json::boolean(u.from_cell));
  return o;
}

/// Joints in degrees, controller convention (as the Python module converts them).
roprec::api::Json degreesJson(const Vec6& q) {
  Vec6 deg;
  for (int i = 0; i < 6; ++i) deg[i] = q[i] / roprec::kDeg;
  return roprec::api::Json::vector(deg);
}

/// One filtered target (roprec_filter_target_hole_json; the Python module's details dict).
roprec::api::Json filteredJson(const roprec::api::Session::Filtered& f) {
  using roprec::api::Json;
  Json o = Json::object();
  o.set("pose_mm", poseJson(f.T_programmed));
  o.set("joints_deg", degreesJson(f.joints_controller));
  o.set("config", Json::str(f.config));
  o.set("residual_um", Json::number(f.residual * 1e6));
  o.set("process", processUsedJson(f.process));
  return o;
}

/// A program's filtered targets (roprec_filter_targets_json; the Python module's filter_targets):
/// a target not filtered keeps its wanted pose and has null joints.
roprec::api::Json filteredBatchJson(const std::vector<roprec::api::Session::Filtered>& f,
                                    const std::vector<Pose>& wanted) {
  using roprec::api::Json;
  Json poses = Json::array();
  Json joints = Json::array();
  Json ok = Json::array();
  Json reasons = Json::array();
  Json process = Json::array();
  for (size_t i = 0; i < f.size(); ++i) {
    poses.push(poseJson(f[i].ok ? f[i].T_programmed : wanted[i]));
    joints.push(f[i].ok ? degreesJson(f[i].joints_controller) : Json());
    ok.push(Json::boolean(f[i].ok));
    reasons.push(f[i].ok ? Json() : Json::str(f[i].reason));
    process.push(processUsedJson(f[i].process));
  }
  Json o = Json::object();
  o.set("poses_mm", std::move(poses));
  o.set("joints_deg", std::move(joints));
  o.set("ok", std::move(ok));
  o.set("reasons", std::move(reasons));
  o.set("process", std::move(process));
  return o;
}

/// Copies a JSON answer into the caller's buffer (UsageError, nothing written, when too small).
void copyJson(const roprec::api::Json& o, char* json, size_t json_len) {
  const std::string text = o.dump(0);
  checkFits(text, json, json_len, "json");
  copyText(text, json);
}

/// The whole prediction job of roprec_predict_file(_ex).
int predictFile(const char* cell_path, const char* program_path,
                const roprec::api::JobOptions& options, const char* json_out_path,
                char* summary_json, size_t summary_len) {
  const std::string cell = pathArg(cell_path, "cell_path");
  const std::string program = pathArg(program_path, "program_path");
  const std::string json_out = optionalArg(json_out_path);
  checkTextBuffer(summary_json, summary_len, "summary_json");
  const roprec::api::PredictionResult r = roprec::api::predictJob(cell, program, options);
  const std::string summary = host::predictionSummary(r).dump(0);
  checkFits(summary, summary_json, summary_len, "summary_json");
  if (!json_out.empty()) roprec::writeFileAtomic(json_out, roprec::api::predictionJson(r).dump());
  copyText(summary, summary_json);
  const std::vector<std::string> failures = host::predictionFailures(r, program);
  if (!failures.empty()) throw ItemFailure{host::joinLines(failures)};
  return ROPREC_OK;
}

/// The whole compensation job of roprec_compensate_file(_ex).
int compensateFile(const char* cell_path, const char* program_path,
                   const roprec::api::CompensationJob& job, const char* out_program_path,
                   const char* targets_out_path, char* summary_json, size_t summary_len) {
  const std::string cell = pathArg(cell_path, "cell_path");
  const std::string program = pathArg(program_path, "program_path");
  const std::string out = pathArg(out_program_path, "out_program_path");
  const std::string targets = optionalArg(targets_out_path);
  checkTextBuffer(summary_json, summary_len, "summary_json");
  if (roprec::api::cellIsMilling(cell))
    return compensateMilling(cell, program, out, targets, job, summary_json, summary_len);

  roprec::api::CompensationResult r = roprec::api::compensateJob(cell, program, job);
  if (const std::string why = host::compensationProblems(r, program); !why.empty())
    throw ItemFailure{why};
  std::vector<std::pair<std::string, std::string>> extra;
  if (!targets.empty())
    extra.emplace_back(targets,
                       roprec::api::compensationTargets(r, program, host::isCsvPath(targets)));
  const std::string summary =
      host::compensationSummary(r, host::compensationPaths(r.context, out, targets)).dump(0);
  return writeCompensation(r.context, out, extra, summary, summary_json, summary_len);
}

/// One roprec_options_set key (see roprec.h). Throws UsageError/InputError on a bad key or value.
/// The verify keys of roprec_options_set (see roprec.h); false: not a verify key.
bool setVerifyOption(roprec_options& o, const std::string& key, const std::string& v) {
  if (key == "write_cell") {
    o.write_cell = v;
  } else if (key == "poses") {
    o.poses = v;
  } else if (key == "date") {
    if (!v.empty()) roprec::api::calibrationDate(v, "");
    o.date = v;
  } else if (key == "identify") {
    const auto s = roprec::identifySetFromName(v);
    if (!s || *s == roprec::IdentifySet::kNone)
      throw roprec::UsageError("identify must be stiffness, geometry or all");
    o.identify = *s;
  } else if (key == "folds") {
    const double k = roprec::api::numbersFromText(v, 1, "folds")[0];
    if (!(k >= 0 && k <= 100 && k == std::floor(k)))
      throw roprec::UsageError("folds must be a whole number in [0, 100]");
    o.folds = static_cast<int>(k);
  } else if (key == "u_rot") {
    o.u_rot_urad = v.empty() ? roprec::api::VerifyJob{}.u_rotation_urad
                             : roprec::api::numbersFromText(v, 1, "u_rot")[0];
    if (!(o.u_rot_urad > 0)) throw roprec::UsageError("u_rot must be > 0 µrad");
  } else {
    return false;
  }
  return true;
}

void setOption(roprec_options& o, const std::string& key, const std::string& v) {
  if (setVerifyOption(o, key, v)) return;
  roprec::api::CompensationJob& job = o.job;
  if (key == "holes") {
    job.job.holes = v.empty() ? std::nullopt : std::optional<std::string>(v);
  } else if (key == "match_tol_mm") {
    job.job.match_tol_mm = roprec::api::numbersFromText(v, 1, "match_tol_mm")[0];
    if (!(job.job.match_tol_mm > 0.0)) throw roprec::UsageError("match_tol_mm must be > 0");
  } else if (key == "uncertainty") {
    if (v != "linear" && v != "montecarlo" && !v.empty())
      throw roprec::UsageError("uncertainty must be linear or montecarlo");
    job.job.uncertainty = v;
  } else if (key == "frame") {
    roprec::api::applyFrameOption(job.job, v);
  } else if (key == "tool") {
    roprec::api::applyToolOption(job.job, v);
  } else if (key == "threads") {
    roprec::api::applyThreadsOption(job.job, v);
  } else if (key == "orientation") {
    job.options.mode = host::orientationMode(v);
  } else if (key == "force") {
    if (v != "0" && v != "1") throw roprec::UsageError("force must be 0 or 1");
    job.force = v == "1";
  } else {
    throw roprec::UsageError(
        "unknown option '" + key +
        "' (holes, match_tol_mm, uncertainty, frame, tool, threads, orientation, force, "
        "write_cell, poses, identify, folds, date, u_rot)");
  }
}

/// A host's hole process (NULL: the cell's) in SI; UsageError for a negative or non-finite value.
roprec::api::HoleProcess holeProcess(const roprec_hole_process* p, const std::string& name) {
  roprec::api::HoleProcess h;
  if (p == nullptr) return h;
  const std::pair<double, const char*> values[] = {{p->diameter_mm, "diameter_mm"},
                                                   {p->depth_mm, "depth_mm"},
                                                   {p->feed_mm_per_rev, "feed_mm_per_rev"},
                                                   {p->spindle_rpm, "spindle_rpm"}};
  for (const auto& [v, field] : values) {
    if (!std::isfinite(v) || v < 0)
      throw roprec::UsageError(name + "." + field + " must be finite and >= 0 (0: the cell's)");
  }
  if (p->tool != nullptr) h.tool = p->tool;
  h.diameter = p->diameter_mm * 1e-3;
  h.depth = p->depth_mm * 1e-3;
  h.feed = p->feed_mm_per_rev * 1e-3;
  h.spindle_rpm = p->spindle_rpm;
  return h;
}

/// The process a call used, into the caller's struct (the tool text truncated to fit).
void processUsed(const roprec::api::ProcessUsed& u, roprec_process_used& out) {
  const size_t n = std::min(u.tool.size(), sizeof out.tool - 1);
  std::memcpy(out.tool, u.tool.data(), n);
  out.tool[n] = '\0';
  out.diameter_mm = u.diameter * 1e3;
  out.depth_mm = u.depth * 1e3;
  out.feed_mm_per_rev = u.feed * 1e3;
  out.spindle_rpm = u.spindle_rpm;
  out.from_cell = u.from_cell ? 1 : 0;
}

/// The targets of roprec_filter_targets(_json), read and filtered in order.
struct FilteredBatch {
  std::vector<Pose> wanted;
  std::vector<roprec::api::Session::Filtered> filtered;
};

FilteredBatch filterBatch(roprec::api::Session& session, size_t count, const double* poses_mm,
                          const double* seed_joints_deg, const roprec_hole_process* processes) {
  FilteredBatch b;
  if (count == 0) return b;
  require(poses_mm, "poses_mm");
  std::vector<Vec6> seeds;
  std::vector<roprec::api::HoleProcess> holes;
  b.wanted.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const std::string n = "poses_mm[" + std::to_string(i) + "]";
    b.wanted.push_back(host::poseFromRowMajorMm(poses_mm + 16 * i, n));
    if (seed_joints_deg != nullptr)
      seeds.push_back(host::jointsFromDeg(seed_joints_deg + 6 * i, "seed_joints_deg"));
    if (processes != nullptr)
      holes.push_back(holeProcess(processes + i, "processes[" + std::to_string(i) + "]"));
  }
  b.filtered = session.filterTargets(b.wanted, seeds, holes);
  return b;
}

/// `target I: reason` of each target not filtered, one a line ("" when all were).
std::string batchFailures(const std::vector<roprec::api::Session::Filtered>& f) {
  std::vector<std::string> failed;
  for (size_t i = 0; i < f.size(); ++i)
    if (!f[i].ok) failed.push_back("target " + std::to_string(i) + ": " + f[i].reason);
  return host::joinLines(failed);
}

/// roprec_predict_joints(_hole)_json: the prediction's figures, with the process used when asked.
int predictJointsJson(roprec_session* s, const double joints_deg[6],
                      const roprec_hole_process* process, bool with_process, char* json,
                      size_t json_len) {
  require(s, "session");
  checkTextBuffer(json, json_len, "json");
  const Vec6 q = host::jointsFromDeg(joints_deg, "joints_deg");
  const roprec::api::Session::JointPrediction p =
      s->session.predictJoints(q, holeProcess(process, "process"));
  if (!p.ok) throw ItemFailure{"no prediction at these joints: " + p.reason};
  roprec::api::Json o = jointPredictionJson(p, q);
  if (with_process) o.set("process", processUsedJson(p.process));
  copyJson(o, json, json_len);
  return ROPREC_OK;
}

/// The verify calls' common end: nothing is written unless every measured item was predicted;
/// then the summary (checked to fit first) and every output.
int writeVerifyOutputs(const roprec::api::VerifyResult& r,
                       const std::vector<std::pair<std::string, std::string>>& out,
                       char* summary_json, size_t summary_len) {
  if (!r.failed.empty()) throw ItemFailure{host::joinLines(r.failed) + "\nnothing written"};
  std::vector<std::string> paths;
  paths.reserve(out.size());
  for (const auto& o : out) paths.push_back(o.first);
  const std::string summary = roprec::api::verifySummaryJson(r, paths).dump(0);
  checkFits(summary, summary_json, summary_len, "summary_json");
  for (const auto& [path, text] : out) roprec::writeFileAtomic(path, text);
  copyText(summary, summary_json);
  return ROPREC_OK;
}

}  // namespace

extern "C" {

ROPREC_API const char* roprec_version(void) { return roprec::api::version(); }

ROPREC_API int roprec_open(const char* cell_path, roprec_session** out, char* err, size_t err_len) {
  if (out != nullptr) *out = nullptr;
  return guarded(err, err_len, [&] {
    require(out, "out");
    const std::string cell = pathArg(cell_path, "cell_path");
    *out = new roprec_session(cell);
    return ROPREC_OK;
  });
}

ROPREC_API void roprec_close(roprec_session* s) { delete s; }

ROPREC_API int roprec_filter_target(roprec_session* s, const double pose_mm[16],
                                    const double* seed_joints_deg, double out_pose_mm[16],
                                    double out_joints_deg[6], char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    require(out_pose_mm, "out_pose_mm");
    require(out_joints_deg, "out_joints_deg");
    const Pose T = host::poseFromRowMajorMm(pose_mm, "pose_mm");
    std::optional<Vec6> seed;
    if (seed_joints_deg != nullptr) seed = host::jointsFromDeg(seed_joints_deg, "seed_joints_deg");
    const roprec::api::Session::Filtered f = s->session.filterTarget(T, seed ? &*seed : nullptr);
    if (!f.ok) throw ItemFailure{"target not filtered: " + f.reason};
    host::poseToRowMajorMm(f.T_programmed, out_pose_mm);
    for (int i = 0; i < 6; ++i) out_joints_deg[i] = f.joints_controller[i] / roprec::kDeg;
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_predict_joints(roprec_session* s, const double joints_deg[6],
                                     double deviation[6], double* U_work_um, char* err,
                                     size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    require(deviation, "deviation");
    const Vec6 q = host::jointsFromDeg(joints_deg, "joints_deg");
    const roprec::api::Session::JointPrediction p = s->session.predictJoints(q);
    if (!p.ok) throw ItemFailure{"no prediction at these joints: " + p.reason};
    for (int i = 0; i < 3; ++i) {
      deviation[i] = p.d_translation[i] * 1e6;
      deviation[3 + i] = p.d_rotation[i] * 1e6;
    }
    if (U_work_um != nullptr) *U_work_um = p.U_work * 1e6;
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_filter_target_hole(roprec_session* s, const double pose_mm[16],
                                         const double* seed_joints_deg,
                                         const roprec_hole_process* process, double out_pose_mm[16],
                                         double out_joints_deg[6], roprec_process_used* used,
                                         char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    require(out_pose_mm, "out_pose_mm");
    require(out_joints_deg, "out_joints_deg");
    const Pose T = host::poseFromRowMajorMm(pose_mm, "pose_mm");
    std::optional<Vec6> seed;
    if (seed_joints_deg != nullptr) seed = host::jointsFromDeg(seed_joints_deg, "seed_joints_deg");
    const roprec::api::HoleProcess hp = holeProcess(process, "process");
    const roprec::api::Session::Filtered f =
        s->session.filterTarget(T, seed ? &*seed : nullptr, hp);
    if (!f.ok) throw ItemFailure{"target not filtered: " + f.reason};
    host::poseToRowMajorMm(f.T_programmed, out_pose_mm);
    for (int i = 0; i < 6; ++i) out_joints_deg[i] = f.joints_controller[i] / roprec::kDeg;
    if (used != nullptr) processUsed(f.process, *used);
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_predict_joints_hole(roprec_session* s, const double joints_deg[6],
                                          const roprec_hole_process* process, double deviation[6],
                                          double* U_work_um, roprec_process_used* used, char* err,
                                          size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    require(deviation, "deviation");
    const Vec6 q = host::jointsFromDeg(joints_deg, "joints_deg");
    const roprec::api::Session::JointPrediction p =
        s->session.predictJoints(q, holeProcess(process, "process"));
    if (!p.ok) throw ItemFailure{"no prediction at these joints: " + p.reason};
    for (int i = 0; i < 3; ++i) {
      deviation[i] = p.d_translation[i] * 1e6;
      deviation[3 + i] = p.d_rotation[i] * 1e6;
    }
    if (U_work_um != nullptr) *U_work_um = p.U_work * 1e6;
    if (used != nullptr) processUsed(p.process, *used);
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_filter_targets(roprec_session* s, size_t count, const double* poses_mm,
                                     const double* seed_joints_deg,
                                     const roprec_hole_process* processes, double* out_poses_mm,
                                     double* out_joints_deg, int* status, char* err,
                                     size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    if (count == 0) return ROPREC_OK;
    require(poses_mm, "poses_mm");
    require(out_poses_mm, "out_poses_mm");
    require(out_joints_deg, "out_joints_deg");
    const std::vector<roprec::api::Session::Filtered> f =
        filterBatch(s->session, count, poses_mm, seed_joints_deg, processes).filtered;
    for (size_t i = 0; i < count; ++i) {
      if (status != nullptr) status[i] = f[i].ok ? ROPREC_OK : ROPREC_ITEM_FAILED;
      if (!f[i].ok) continue;
      host::poseToRowMajorMm(f[i].T_programmed, out_poses_mm + 16 * i);
      for (int j = 0; j < 6; ++j)
        out_joints_deg[6 * i + j] = f[i].joints_controller[j] / roprec::kDeg;
    }
    if (const std::string failed = batchFailures(f); !failed.empty()) throw ItemFailure{failed};
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_error_kind(void) { return g_error_kind; }

ROPREC_API int roprec_session_info(roprec_session* s, char* json, size_t json_len, char* err,
                                   size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    checkTextBuffer(json, json_len, "json");
    const roprec::api::PredictionContext& c = s->session.context();
    using roprec::api::Json;
    Json o = Json::object();
    o.set("cell_path", Json::str(s->cell_path));
    o.set("cell", Json::str(c.cell.name));
    o.set("robot", Json::str(c.robot.card.name));
    o.set("process", Json::str(c.process_description));
    o.set("tool_pose_mm", poseJson(c.tool.T_flange_tcp));
    o.set("workobject_pose_mm", poseJson(c.cell.T_base_wobj));
    const std::string text = o.dump(0);
    checkFits(text, json, json_len, "json");
    copyText(text, json);
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_predict_joints_json(roprec_session* s, const double joints_deg[6], char* json,
                                          size_t json_len, char* err, size_t err_len) {
  return guarded(err, err_len,
                 [&] { return predictJointsJson(s, joints_deg, nullptr, false, json, json_len); });
}

ROPREC_API int roprec_predict_joints_hole_json(roprec_session* s, const double joints_deg[6],
                                               const roprec_hole_process* process, char* json,
                                               size_t json_len, char* err, size_t err_len) {
  return guarded(err, err_len,
                 [&] { return predictJointsJson(s, joints_deg, process, true, json, json_len); });
}

ROPREC_API int roprec_filter_target_hole_json(roprec_session* s, const double pose_mm[16],
                                              const double* seed_joints_deg,
                                              const roprec_hole_process* process, char* json,
                                              size_t json_len, char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    checkTextBuffer(json, json_len, "json");
    const Pose T = host::poseFromRowMajorMm(pose_mm, "pose_mm");
    std::optional<Vec6> seed;
    if (seed_joints_deg != nullptr) seed = host::jointsFromDeg(seed_joints_deg, "seed_joints_deg");
    const roprec::api::Session::Filtered f =
        s->session.filterTarget(T, seed ? &*seed : nullptr, holeProcess(process, "process"));
    if (!f.ok) throw ItemFailure{"target not filtered: " + f.reason};
    copyJson(filteredJson(f), json, json_len);
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_filter_targets_json(roprec_session* s, size_t count, const double* poses_mm,
                                          const double* seed_joints_deg,
                                          const roprec_hole_process* processes, char* json,
                                          size_t json_len, char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    require(s, "session");
    checkTextBuffer(json, json_len, "json");
    const FilteredBatch b = filterBatch(s->session, count, poses_mm, seed_joints_deg, processes);
    copyJson(filteredBatchJson(b.filtered, b.wanted), json, json_len);
    if (const std::string failed = batchFailures(b.filtered); !failed.empty())
      throw ItemFailure{failed};
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_predict_file(const char* cell_path, const char* program_path,
                                   const char* holes_path, const char* json_out_path,
                                   char* summary_json, size_t summary_len, char* err,
                                   size_t err_len) {
  return guarded(err, err_len, [&] {
    roprec::api::JobOptions options;
    if (const std::string holes = optionalArg(holes_path); !holes.empty()) options.holes = holes;
    return predictFile(cell_path, program_path, options, json_out_path, summary_json, summary_len);
  });
}

ROPREC_API int roprec_predict_file_ex(const char* cell_path, const char* program_path,
                                      const roprec_options* options, const char* json_out_path,
                                      char* summary_json, size_t summary_len, char* err,
                                      size_t err_len) {
  return guarded(err, err_len, [&] {
    require(options, "options");
    return predictFile(cell_path, program_path, options->job.job, json_out_path, summary_json,
                       summary_len);
  });
}

ROPREC_API int roprec_compensate_file(const char* cell_path, const char* program_path,
                                      const char* holes_path, const char* out_program_path,
                                      const char* orientation, const char* targets_out_path,
                                      char* summary_json, size_t summary_len, char* err,
                                      size_t err_len) {
  return guarded(err, err_len, [&] {
    roprec::api::CompensationJob job;
    job.options.mode = host::orientationMode(optionalArg(orientation));
    if (const std::string holes = optionalArg(holes_path); !holes.empty()) job.job.holes = holes;
    return compensateFile(cell_path, program_path, job, out_program_path, targets_out_path,
                          summary_json, summary_len);
  });
}

ROPREC_API int roprec_compensate_file_ex(const char* cell_path, const char* program_path,
                                         const roprec_options* options,
                                         const char* out_program_path, const char* targets_out_path,
                                         char* summary_json, size_t summary_len, char* err,
                                         size_t err_len) {
  return guarded(err, err_len, [&] {
    require(options, "options");
    return compensateFile(cell_path, program_path, options->job, out_program_path, targets_out_path,
                          summary_json, summary_len);
  });
}

ROPREC_API int roprec_options_new(roprec_options** out, char* err, size_t err_len) {
  if (out != nullptr) *out = nullptr;
  return guarded(err, err_len, [&] {
    require(out, "out");
    *out = new roprec_options();
    return ROPREC_OK;
  });
}

ROPREC_API void roprec_options_free(roprec_options* options) { delete options; }

ROPREC_API int roprec_options_set(roprec_options* options, const char* key, const char* value,
                                  char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    require(options, "options");
    require(key, "key");
    require(value, "value");
    roprec_options next = *options;  // unchanged on a refused value
    setOption(next, key, value);
    *options = std::move(next);
    return ROPREC_OK;
  });
}

ROPREC_API int roprec_verify_file(const char* cell_path, const char* program_path,
                                  const char* measured_path, const char* holes_path,
                                  const char* registration, const char* json_out_path,
                                  const char* new_card_out_path, char* summary_json,
                                  size_t summary_len, char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    const std::string cell = pathArg(cell_path, "cell_path");
    const std::string program = pathArg(program_path, "program_path");
    roprec::api::VerifyJob job;
    job.measured = pathArg(measured_path, "measured_path");
    const std::string holes = optionalArg(holes_path);
    const std::string json_out = optionalArg(json_out_path);
    const std::string card_out = optionalArg(new_card_out_path);
    checkTextBuffer(summary_json, summary_len, "summary_json");
    if (!holes.empty()) job.job.holes = holes;
    job.registration = host::registration(optionalArg(registration));
    job.calibrate = !card_out.empty();
    const roprec::api::VerifyResult r = roprec::api::verifyJob(cell, program, job);
    return writeVerifyOutputs(r, host::verifyOutputs(r, job, json_out, card_out), summary_json,
                              summary_len);
  });
}

ROPREC_API int roprec_verify_file_ex(const char* cell_path, const char* program_path,
                                     const char* measured_path, const char* registration,
                                     const roprec_options* options, const char* json_out_path,
                                     const char* new_card_out_path, char* summary_json,
                                     size_t summary_len, char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    require(options, "options");
    const std::string cell = pathArg(cell_path, "cell_path");
    roprec::api::VerifyJob job;
    job.job = options->job.job;
    job.poses = options->poses;
    job.measured = optionalArg(measured_path);
    const std::string program = optionalArg(program_path);
    if (job.measured.empty() && job.poses.empty())
      throw roprec::UsageError("give measured_path and/or the option \"poses\"");
    if (!job.measured.empty() && program.empty())
      throw roprec::UsageError("program_path is NULL (a measured file needs its program)");
    job.identify = options->identify;
    job.folds = options->folds;
    job.date = options->date;
    job.u_rotation_urad = options->u_rot_urad;
    const std::string json_out = optionalArg(json_out_path);
    const std::string card_out = optionalArg(new_card_out_path);
    checkTextBuffer(summary_json, summary_len, "summary_json");
    job.registration = host::registration(optionalArg(registration));
    job.calibrate = !card_out.empty();
    if (!options->write_cell.empty() && !job.calibrate &&
        job.registration == roprec::Registration::kNone)
      throw roprec::UsageError("write_cell needs a registration and/or new_card_out_path");
    const roprec::api::VerifyResult r = roprec::api::verifyJob(cell, program, job);
    return writeVerifyOutputs(r,
                              host::verifyOutputs(r, job, json_out, card_out, options->write_cell),
                              summary_json, summary_len);
  });
}

ROPREC_API int roprec_plan_test_file(const char* cell_path, const double region_mm[6], int count,
                                     const char* out_path, char* summary_json, size_t summary_len,
                                     char* err, size_t err_len) {
  return guarded(err, err_len, [&] {
    const std::string cell = pathArg(cell_path, "cell_path");
    const std::string out = pathArg(out_path, "out_path");
    if (region_mm == nullptr) throw roprec::UsageError("region_mm is NULL");
    checkTextBuffer(summary_json, summary_len, "summary_json");
    const roprec::Vec3 lo(region_mm[0], region_mm[1], region_mm[2]);
    const roprec::Vec3 hi(region_mm[3], region_mm[4], region_mm[5]);
    const roprec::api::PlanTestResult r = roprec::api::planTestJob(cell, lo, hi, count);
    const roprec::postproc::DrillProgramText t = roprec::api::planTestProgram(r, out);
    const std::string summary =
        roprec::api::planTestSummaryJson(r, roprec::postproc::drillProgramPaths(t, out)).dump(0);
    checkFits(summary, summary_json, summary_len, "summary_json");
    roprec::postproc::saveDrillProgram(t, out);
    copyText(summary, summary_json);
    return ROPREC_OK;
  });
}

}  // extern "C"
