#pragma once
/// \file host_common.hpp
/// What the C ABI (roprec_c.cpp) and the Python module (plugin/python) share: host units and
/// layouts (row-major 4x4 poses in mm, joints in degrees) to and from the job API's SI types,
/// the one-line summary JSON of predict/compensate, and the messages naming the items that
/// failed. Internal: not installed.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"
#include "compensator/support/rotation.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/milling_files.hpp"
#include "plugin/api/verify.hpp"
#include "plugin/report/verify_json.hpp"
#include "postproc/program.hpp"

namespace roprec::host {

/// Row-major 4x4 (mm) -> rigid pose (m). UsageError unless finite, last row 0 0 0 1 (1e-9) and
/// the rotation orthonormal (1e-6) and right-handed. The rotation is taken as given.
inline Pose poseFromRowMajorMm(const double* m, const std::string& name) {
  if (m == nullptr) throw UsageError(name + " is NULL");
  for (int i = 0; i < 16; ++i) {
    if (!std::isfinite(m[i]))
      throw UsageError(name + ": element " + std::to_string(i) + " is not finite");
  }
  if (std::abs(m[12]) > 1e-9 || std::abs(m[13]) > 1e-9 || std::abs(m[14]) > 1e-9 ||
      std::abs(m[15] - 1.0) > 1e-9) {
    throw UsageError(name + ": the last row must be 0 0 0 1");
  }
  Mat3 R;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R(r, c) = m[4 * r + c];
  }
  const double orth = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (!(orth <= 1e-6) || !(R.determinant() > 0)) {
    throw UsageError(name + ": the rotation is not orthonormal and right-handed (max |RᵀR − I| = " +
                     api::formatNumber(orth, -1) + ")");
  }
  Pose T = Pose::Identity();
  T.linear() = R;
  T.translation() = Vec3(m[3], m[7], m[11]) * 1e-3;
  return T;
}

/// Pose (m) -> row-major 4x4 (mm); the last row is exactly 0 0 0 1.
inline void poseToRowMajorMm(const Pose& T, double* out) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[4 * r + c] = T.linear()(r, c);
    out[4 * r + 3] = T.translation()[r] * 1e3;
  }
  out[12] = 0.0;
  out[13] = 0.0;
  out[14] = 0.0;
  out[15] = 1.0;
}

/// 6 joints in degrees -> rad; UsageError when NULL or not finite.
inline Vec6 jointsFromDeg(const double* j, const std::string& name) {
  if (j == nullptr) throw UsageError(name + " is NULL");
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    if (!std::isfinite(j[i]))
      throw UsageError(name + ": joint " + std::to_string(i + 1) + " is not finite");
    q[i] = j[i] * kDeg;
  }
  return q;
}

/// "keep" (also empty), "flip-free", "stiffest".
inline OrientationMode orientationMode(const std::string& text) {
  const std::string m = text.empty() ? "keep" : text;
  if (m == "keep") return OrientationMode::kKeep;
  if (m == "flip-free") return OrientationMode::kFlipFree;
  if (m == "stiffest") return OrientationMode::kStiffest;
  throw UsageError("orientation must be keep, flip-free or stiffest (got '" + m + "')");
}

/// True when the export named `path` is CSV (else JSON), as `roprec compensate --targets`.
inline bool isCsvPath(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
}

/// One line per problem, at most `max_lines` of them.
inline std::string joinLines(const std::vector<std::string>& lines, size_t max_lines = 50) {
  std::string s;
  for (size_t i = 0; i < lines.size() && i < max_lines; ++i) {
    if (i) s += "\n";
    s += lines[i];
  }
  if (lines.size() > max_lines)
    s += "\n… and " + std::to_string(lines.size() - max_lines) + " more";
  return s;
}

/// The holes a prediction could not handle, `hole ID (FILE:LINE): verdict: reason`.
inline std::vector<std::string> predictionFailures(const api::PredictionResult& r,
                                                   const std::string& program) {
  std::vector<std::string> out;
  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HolePrediction& h = r.holes[i];
    if (h.status == HoleStatus::kOk) continue;
    out.push_back(api::holeWhere(h.id, r.context.job.requests[i].line, program) + ": " +
                  verdictAndReason(h.verdict, h.reason));
  }
  return out;
}

/// Why a compensation may not be written (empty when it may).
inline std::string compensationProblems(const api::CompensationResult& r,
                                        const std::string& program) {
  if (r.writable) return {};
  std::vector<std::string> problems;
  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HoleCompensation& h = r.holes[i];
    if (h.ok) continue;
    problems.push_back(api::holeWhere(h.id, r.context.job.requests[i].line, program) +
                       ": not compensated: " + h.reason);
  }
  problems.insert(problems.end(), r.refused.begin(), r.refused.end());
  const std::string why =
      r.why_not_writable.empty() ? "nothing written" : r.why_not_writable + "; nothing written";
  return problems.empty() ? why : joinLines(problems) + "\n" + why;
}

/// Why a milling compensation may not be written (empty when it may).
inline std::string millingProblems(const api::MillingFilesResult& res) {
  const api::MillingCompensationResult& r = res.job;
  if (r.failures.empty() && r.refused.empty()) return {};
  std::vector<std::string> problems = r.failures;
  problems.insert(problems.end(), r.refused.begin(), r.refused.end());
  return joinLines(problems) + "\n" + std::to_string(r.failures.size()) + " of " +
         std::to_string(r.pointCount()) + " path points not compensated, " +
         std::to_string(r.refused.size()) + " edits refused; nothing written";
}

/// The "summary" object of the prediction JSON plus "failed".
inline api::Json predictionSummary(const api::PredictionResult& r) {
  api::Json s = api::summaryJson(r.summary);
  s.set("failed", api::Json::integer(r.failed()));
  return s;
}

inline api::Json meanMax(const std::vector<double>& v) {
  api::Json j = api::Json::object();
  if (v.empty()) {
    j.set("mean", api::Json());
    j.set("max", api::Json());
    return j;
  }
  double mean = 0;
  for (const double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  j.set("mean", api::Json::number(mean, 4));
  j.set("max", api::Json::number(*std::max_element(v.begin(), v.end()), 4));
  return j;
}

inline api::Json pathList(const std::vector<std::string>& paths) {
  api::Json a = api::Json::array();
  for (const auto& p : paths) a.push(api::Json::str(p));
  return a;
}

/// The files a drilling compensation writes: the program (KRL: .src and .dat) and the export.
inline std::vector<std::string> compensationPaths(const api::PredictionContext& c,
                                                  const std::string& out,
                                                  const std::string& targets) {
  std::vector<std::string> paths = postproc::outputPaths(*c.job.program, out);
  if (!targets.empty()) paths.push_back(targets);
  return paths;
}

inline api::Json compensationSummary(const api::CompensationResult& r,
                                     const std::vector<std::string>& written) {
  api::Json s = api::Json::object();
  s.set("orientation", api::Json::str(r.orientation));
  s.set("holes", api::Json::integer(static_cast<std::int64_t>(r.holes.size())));
  s.set("compensated", api::Json::integer(static_cast<std::int64_t>(r.holes.size()) - r.failed));
  s.set("failed", api::Json::integer(r.failed));
  s.set("error_before_um", meanMax(r.summary.error_before_um));
  s.set("residual_after_um", meanMax(r.summary.residual_after_um));
  s.set("conform_before", api::Json::integer(r.summary.conform_before));
  s.set("conform_after", api::Json::integer(r.summary.conform_after));
  s.set("jumps_before", api::Json::integer(r.summary.jumps_before));
  s.set("jumps_after", api::Json::integer(r.summary.jumps_after));
  s.set("written", pathList(written));
  return s;
}

inline api::Json millingSummary(const api::MillingFilesResult& res) {
  const api::MillingPointStats& st = res.stats;
  const auto meanMaxOf = [&](double sum, double max) {
    api::Json j = api::Json::object();
    if (st.points == 0) {
      j.set("mean", api::Json());
      j.set("max", api::Json());
      return j;
    }
    j.set("mean", api::Json::number(sum / static_cast<double>(st.points), 4));
    j.set("max", api::Json::number(max, 4));
    return j;
  };
  api::Json s = api::Json::object();
  s.set("process", api::Json::str("milling"));
  s.set("points", api::Json::integer(static_cast<std::int64_t>(st.points)));
  s.set("failed", api::Json::integer(static_cast<std::int64_t>(st.failed)));
  s.set("deviation_before_um", meanMaxOf(st.before_sum_um, st.before_max_um));
  s.set("residual_after_um", meanMaxOf(st.after_sum_um, st.after_max_um));
  s.set("written", pathList(res.written));
  return s;
}

/// "none" (also empty), "translation", "rigid".
inline Registration registration(const std::string& text) {
  const std::string t = text.empty() ? "none" : text;
  const std::optional<Registration> r = registrationFromName(t);
  if (!r) throw UsageError("registration must be none, translation or rigid (got '" + t + "')");
  return *r;
}

/// The texts `roprec verify` writes, rendered before anything is written: (path, text) for the
/// JSON (when json_out is not empty) and the calibrated card (when card_out is not empty).
/// The files a verify writes: the JSON, the calibrated card (not when the held-out validation
/// refused it: VerifyResult::card_refused), the new cell (<part_registration> of the registered
/// part, robot = the new card when one is written; not when the card was refused).
inline std::vector<std::pair<std::string, std::string>> verifyOutputs(
    const api::VerifyResult& r, const api::VerifyJob& job, const std::string& json_out,
    const std::string& card_out, const std::string& cell_out = "") {
  std::vector<std::pair<std::string, std::string>> out;
  if (!json_out.empty()) out.emplace_back(json_out, api::verifyJson(r).dump());
  const bool card_ok = !card_out.empty() && r.card_refused.empty();
  if (card_ok) {
    const std::string& file = job.measured.empty() ? job.poses : job.measured;
    // the file's name without its folder, as the CLI writes it ("\\" ends a folder on Windows too)
    const std::string name = file.substr(file.find_last_of(platform::kPathSeparators) + 1);
    out.emplace_back(card_out, api::calibratedCardText(r, name, card_out));
  }
  if (!cell_out.empty() && (card_out.empty() || card_ok))
    out.emplace_back(cell_out, api::calibratedCellText(r, cell_out, card_ok ? card_out : ""));
  return out;
}

}  // namespace roprec::host
