#pragma once
/// \file report.hpp
/// The self-contained HTML report of `roprec predict` (and of `roprec compensate`, which adds
/// before/after maps): inline SVG deviation maps over the work area like Ferreras-Higuero et al.
/// (RCIM 2020) Fig. 13–15 (δrobot, δwork and U_work coloured over the hole positions, wrist/arm
/// configuration changes visible), a per-hole table, the uncertainty budget, verdict counts and
/// the capability summary. No network, no external scripts or fonts; deterministic bytes.

#include <optional>
#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"

namespace roprec::api {

struct ReportHole {
  const HolePrediction* prediction{nullptr};
  Pose T_W_tcp{Pose::Identity()};  ///< nominal TCP pose at the drill point, base frame
  /// compensate only: the residual predicted after compensation and the programmed pose
  std::optional<double> residual_um;
  std::optional<Pose> T_W_programmed;
  std::optional<double> rotation_about_axis_deg;
  const HolePrediction* after{nullptr};  ///< compensate: prediction at the programmed pose
};

struct ReportInput {
  std::string title;               ///< e.g. "roprec prediction — housing.src"
  std::string robot;               ///< robot name + model
  std::string cell;                ///< cell name and file
  std::string program;             ///< program file
  std::string process;             ///< process description
  std::string uncertainty_method;  ///< "linearised" / "Monte Carlo (N, seed)"
  std::string uncertainty_source;
  double default_tolerance_mm{0.2};
  /// How program frames and the tool were resolved (--frame/--tool), stated in the header.
  std::vector<std::string> resolutions;
  std::vector<ReportHole> holes;
  CapabilitySummary summary;
  bool compensation{false};  ///< adds the before/after maps and residual columns
  std::string generator{"roprec 0.1.0"};
};

/// The whole HTML document.
std::string renderReport(const ReportInput& in);

}  // namespace roprec::api
