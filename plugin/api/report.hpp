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
#include "plugin/api/deviation_split.hpp"

namespace roprec {
struct RobotCard;
}

namespace roprec::api {

struct ReportHole {
  const HolePrediction* prediction{nullptr};
  Pose T_W_tcp{Pose::Identity()};  ///< nominal TCP pose at the drill point, base frame
  /// compensate only: the residual predicted after compensation and the programmed pose
  std::optional<double> residual_um;
  std::optional<Pose> T_W_programmed;
  std::optional<double> rotation_about_axis_deg;
  const HolePrediction* after{nullptr};  ///< compensate: prediction at the programmed pose
  /// compensate: the configuration flags of the programmed (compensated) target
  std::optional<std::string> config_after;
  /// compensate: the program's flags at the hole (HoleCompensation::config_before; empty: the
  /// flags of the predicted posture are shown as "before")
  std::string config_before;
  /// compensate: why the programmed rotation about the drill axis was not kept ("" when kept)
  std::string rotation_reason;
  /// compensate: why the written flags differ from the program's ("" when kept)
  std::string config_reason;
  /// Why: δrobot split into gravity, tool weight, process load and controller reference.
  std::optional<DeviationSplit> split;
};

struct ReportInput {
  /// The joints of the table are shown as the controller shows them (toControllerJoints of this
  /// card: θ_ctrl,i = sign_i·θ_urdf,i + offset_i, J3 += j23_coupling·θ_urdf,2, e.g. FANUC J3 =
  /// J3_urdf − J2_urdf); nullptr: the URDF convention. The table head says which.
  const RobotCard* card{nullptr};
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
  /// The robot card's estimated numbers (cardEstimates), stated in the header.
  std::vector<std::string> card_estimates;
  std::vector<ReportHole> holes;
  /// The part (workobject) frame the maps are drawn in, and its name ("cell workobject",
  /// "BASE_DATA[2]", ...): hole positions and directions are expressed in it, axes named after it.
  Pose T_W_part{Pose::Identity()};
  std::string part_frame{"robot base"};
  CapabilitySummary summary;
  bool compensation{false};  ///< adds the before/after maps and residual columns
  std::string generator{"roprec 0.1.0"};
};

/// Above this many holes the maps aggregate holes into bins (the worst value and verdict of each
/// bin) and the per-hole table lists the holes that do not conform plus the first ones, so a
/// 20,000-hole report stays small and opens quickly (docs/reports.md §4).
inline constexpr size_t kReportAggregateAbove = 2000;

struct PredictionContext;

/// The reports' colour map (viridis, see report.cpp) at t ∈ [0, 1] (clamped; NaN → 0) as "#rrggbb".
std::string viridisHex(double t);

/// Fills what the report derives from the job: the part frame (the program frame every hole
/// shares, else the cell's <workobject>, named after it) and each predicted hole's δrobot split
/// (splitRobotDeviations with the context's model and tool). Call after `in.holes` has one entry
/// per context.job.requests entry, in that order. Throws std::invalid_argument otherwise. The
/// split runs on `threads` workers (the same bytes).
void addPartFrameAndSplit(ReportInput& in, const PredictionContext& c, int threads = 1);

/// The whole HTML document.
std::string renderReport(const ReportInput& in);

/// The reports' inline table script (no network, no library): a click on a head of the table
/// `#holetable` sorts its body by that column (numbers numerically, `data-t="1"` heads as text;
/// again: the other way; ties keep program order) and marks the head `aria-sort`; the checkbox
/// `#failonly` toggles the class `fonly` on the table (CSS hides `tr.pass` under it).
const char* reportTableScript();

}  // namespace roprec::api
