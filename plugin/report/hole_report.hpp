#pragma once
/// \file hole_report.hpp
/// The self-contained HTML report of `roprec predict` (and of `roprec compensate`, which adds
/// before/after maps): inline SVG deviation maps over the work area like Ferreras-Higuero et al.
/// (RCIM 2020) Fig. 13–15 (δrobot, δwork and U_work coloured over the hole positions, wrist/arm
/// configuration changes visible), a per-hole table, the uncertainty budget, verdict counts and
/// the capability summary. No network, no external scripts or fonts; deterministic bytes.
/// Drawn by hole_report.cpp and one file per section (hole_sections.hpp: maps, budget, table).

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "compensator/precision/prediction.hpp"
#include "plugin/api/deviation_split.hpp"

namespace roprec {
struct RobotCard;
}

namespace roprec::api {

/// What the deviation maps read of a hole's prediction (a large job's maps: the holes binned).
struct MapFacts {
  std::string id;
  HoleStatus status{HoleStatus::kOk};
  Verdict verdict{Verdict::kConforms};
  int branch{0};
  Vec3 d_robot{Vec3::Zero()};
  Vec3 d_work{Vec3::Zero()};
  double position_error{0};
  double U_work_exact{0};
  double tolerance{0};
};

/// What the report shows of a hole's prediction (HolePrediction's fields the sections read): a
/// compact copy, so a streamed job keeps ~0.6 kB a hole for its report instead of every
/// prediction (reportPrediction).
struct ReportPrediction : MapFacts {
  std::string reason;
  std::string config;
  Vec6 joints{Vec6::Zero()};
  Vec3 d_mach{Vec3::Zero()};
  double axis_tilt{0};
  InlineVector<BudgetTerm, kMaxBudgetTerms> budget;
  double u_robot{0}, u_mach{0}, u_work{0};
  double k{0};
  double U_robot{0}, U_mach{0}, U_work{0};
  double process_share{0};
  double mc_time{0};
  double diameter{0};
};

/// The report's copy of a prediction.
ReportPrediction reportPrediction(const HolePrediction& p);
/// The same into `r` (its strings' storage reused).
void reportPrediction(const HolePrediction& p, ReportPrediction& r);

/// A hole of a large streamed prediction's report as its maps need it (ReportInput::mapped,
/// ~0.16 kB): what the maps read of its prediction, its nominal drill point and drilling axis
/// (base frame). Its table row is rendered and its budget counted as it goes past.
struct MappedHole {
  MapFacts facts;
  Vec3 position{Vec3::Zero()};
  Vec3 axis{Vec3::UnitZ()};
};

/// The uncertainty budget summed over the predicted holes, in program order (the budget section).
struct BudgetSums {
  struct Term {
    std::string name;
    bool process{false};
    double sum_u{0}, max_u{0}, sum_share{0};
    int n{0};
  };
  struct Sum {
    double sum{0}, max{0};
    void add(double v) {
      sum += v;
      max = std::max(max, v);
    }
  };
  int n_ok{0};
  double k{0};  ///< coverage factor of the first predicted hole
  std::vector<Term> terms;
  std::array<Sum, 6> combined{};  ///< u_robot u_mach u_work U_robot U_mach U_work
  Sum process_share;
  /// Counts a predicted hole (status kOk).
  void add(const ReportPrediction& p);
};

/// A hole of a streamed prediction's report (ReportInput::predicted): its prediction, the
/// nominal drill point and drilling axis (base frame: T_W_tcp's translation and z column) and
/// its δrobot split.
struct PredictedHole {
  ReportPrediction prediction;
  Vec3 position{Vec3::Zero()};
  Vec3 axis{Vec3::UnitZ()};
  std::optional<DeviationSplit> split;
};

/// A run of a large streamed prediction report's table rows rendered ahead, as its holes went
/// past (RowsAheadRenderer): the items of the table's script array for rows [first, first +
/// count) (",\n" before each but the job's first), rendered with the first `terms` budget-term
/// columns and with or without the δrobot split columns.
struct RenderedRows {
  size_t first{0}, count{0};
  size_t terms{0};
  bool split_columns{false};
  std::string text;
  /// Where a row takes the columns the table may gain after it was rendered, two offsets into
  /// `text` a row: a predicted hole's row the place of the δrobot split cells and the place after
  /// its last budget-term cell; another row the digits of its reason cell's colspan (the first
  /// offset with kColspanMark set) and their count.
  std::vector<std::uint32_t> marks;
  static constexpr std::uint32_t kColspanMark = 0x80000000u;
};

/// What a large streamed prediction's report (ReportInput::mapped) counts of its holes as they go
/// past, in program order: the sections' figures that read every hole.
struct StreamedTotals {
  std::vector<std::string> terms;  ///< budget terms, first-seen order (the table's columns)
  bool split{false};               ///< a hole had a δrobot split (the table's split columns)
  long not_conforming{0};          ///< holes that do not conform (the table's filter)
  /// the IK branches of the predicted holes with the configuration of their first hole, in the
  /// order first seen (the maps' legend)
  std::vector<std::pair<int, std::string>> branches;
  BudgetSums budget;
  /// Counts the next holes, in order.
  void add(std::span<const PredictedHole> holes);
};

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
  /// A prediction report's holes kept compactly as they stream past (instead of `holes`, which
  /// must then be empty).
  std::vector<PredictedHole> predicted;
  /// A large prediction report's holes as its maps need them (instead of `holes` and
  /// `predicted`, which must then be empty): the other sections read `totals`, and every row
  /// is in `rows_ahead`.
  std::vector<MappedHole> mapped;
  StreamedTotals totals;
  /// A large job's rows of `predicted` rendered ahead (RowsAheadRenderer), in order from the first
  /// hole (they may end before the last): written as they are where the table has the columns
  /// they were rendered with, the others rendered again.
  std::vector<RenderedRows> rows_ahead;
  /// The part (workobject) frame the maps are drawn in, and its name ("cell workobject",
  /// "BASE_DATA[2]", ...): hole positions and directions are expressed in it, axes named after it.
  Pose T_W_part{Pose::Identity()};
  std::string part_frame{"robot base"};
  CapabilitySummary summary;
  bool compensation{false};  ///< adds the before/after maps and residual columns
  std::string generator{"roprec 0.1.0"};
  /// Workers that render a large job's table rows (the bytes do not depend on the count).
  int threads{1};
};

/// Above this many holes the maps aggregate holes into bins (the worst value and verdict of each
/// bin) and the per-hole table lists the holes that do not conform plus the first ones, so a
/// 20,000-hole report stays small and opens quickly (docs/reports.md §4).
inline constexpr size_t kReportAggregateAbove = 2000;

/// The whole HTML document (plugin/api/report_input.hpp fills the part frame and the split).
std::string renderReport(const ReportInput& in);
/// The same bytes given to `sink` piece by piece, in order: the rows rendered ahead straight
/// from `in`, the rest in pieces of about 1 MiB (no whole-document string).
void renderReport(const ReportInput& in, const std::function<void(std::string_view)>& sink);

/// Renders the table rows of a large streamed prediction's report (more than
/// kReportAggregateAbove holes) as its holes go past: the bytes renderReport writes for them,
/// given the budget terms and the split seen so far (a row rendered before a hole brings a new
/// term or the first split is rendered again by renderReport).
class RowsAheadRenderer {
 public:
  /// `card`: ReportInput::card of the report (the joints' convention); must outlive this.
  explicit RowsAheadRenderer(const RobotCard* card);
  /// The rows of the job's next holes `holes`, in order, the first being row `first`, on
  /// `threads` workers (the same bytes for any count), appended to `out` as runs.
  void render(std::span<const PredictedHole> holes, size_t first, int threads,
              std::vector<RenderedRows>& out);

 private:
  ReportInput in_;                  ///< the card only
  std::vector<std::string> terms_;  ///< budget terms, first-seen order
  bool split_{false};               ///< a hole had a split
  int prev_branch_{-1};             ///< IK branch of the last predicted hole
};

/// The reports' inline table script (no network, no library): a click on a head of the table
/// `#holetable` sorts its body by that column (numbers numerically, `data-t="1"` heads as text;
/// again: the other way; ties keep program order) and marks the head `aria-sort`; the checkbox
/// `#failonly` toggles the class `fonly` on the table (CSS hides `tr.pass` under it).
const char* reportTableScript();

}  // namespace roprec::api
