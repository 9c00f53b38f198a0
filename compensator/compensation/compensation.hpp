#pragma once
/// \file compensation.hpp
/// Pre-offsetting drill targets so that the predicted real hole lands on the nominal one, and
/// choosing the free rotation ψ about each drill axis (NLopt + dynamic programming).
///
/// Per hole, for a rotation ψ about the drill axis and an IK branch:
///   1. desired TCP  T_d = T_nom · Rz(ψ); link-side joints θ_d = IK(T_d) in the branch — the IK of
///      the real robot (realIk: a calibrated robot's analytic solution refined by Newton on its
///      calibrated chain, docs/model.md §6.8);
///   2. motor-side command θ_m = θ_d + K_eff⁻¹ τ(θ_d) — exact, the inverse of deflection.hpp
///      (τ with link/tool weight and the process wrench following the real = desired tool axis);
///      a controller that compensates gravity itself adds its own offset, which is removed here;
///   3. programmed target = the controller's rigid FK of θ_m (FK_nom: the card's URDF), with the
///      configuration flags of θ_m.
/// Every target of a drill cycle moves with the drill point (T ← ΔT · T · Rz(ψ), ΔT = T_prog T_d⁻¹)
/// so the drilling axis stays straight. Re-predicting the programmed pose gives θ = θ_d exactly
/// (to the equilibrium tolerance), hence a systematic residual at solver precision.
///
/// Orientation modes (`--orientation`, docs/configuration.md §6):
///   keep       ψ = 0 and positions only: the programmed orientation is the original one to the
///              last bit; the programmed position is iterated until the predicted real TCP
///              position is the nominal one (the real drill axis keeps its small tilt);
///   flip-free  keeps the programmed rotation (ψ = 0) unless it is not admissible: the constraints
///              are the joint limits, |θ5| ≥ margin, |Δθ4|, |Δθ6| ≤ threshold between consecutive
///              holes of one face (axes within 10°; a face change is a repositioning move) and the
///              programmed IK branch (unless a change is allowed). Among admissible sequences the
///              objective is lexicographic: (1) fewest holes with ψ ≠ 0, (2) smallest Σ|ψ| (ties
///              go to the smallest change), (3) joint travel and limit/wrist proximity. Every hole
///              with ψ ≠ 0 carries its reason (limit, wrist margin, or the jump ψ = 0 would make);
///   stiffest   minimise the predicted U_work (stiffness proxy) under the same constraints; a hole
///              whose keep result is stiffer goes back to ψ = 0 when the constraints allow it, and
///              a hole at ψ = 0 takes its keep result (its exact compensation is made only where
///              keep fails); the gain U_work(keep) − U_work per hole and in the summary.
/// Sequence level: dynamic programming over a ψ grid (ψ = 0 is always node 0) for the whole
/// program (not hole by hole), then NLopt (COBYLA, 1-D, constraints as above) refines each changed
/// hole's ψ with its neighbours fixed (flip-free: smallest |ψ|; stiffest: smallest U).
///
/// Configuration flags: the program's flags (`HoleRequest::config`, else `written_config`) are
/// kept when the compensated target is reached with them in the planned posture (same branch,
/// same joints up to whole turns; a joint within kFlagBoundaryTolerance of a flag boundary
/// matches either side); otherwise the flags of the command are written and the change is
/// listed with its reason (`config_changed`, `config_reason`).
#include <cstddef>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"
#include "compensator/support/inline_text.hpp"

namespace roprec {

enum class OrientationMode { kKeep, kFlipFree, kStiffest };

/// Holes predicted, finished (stage 5) and handed to a CompensationSink at a time (the default of
/// CompensationOptions::block).
inline constexpr std::size_t kCompensationBlock = 2048;
const char* orientationModeName(OrientationMode m);

struct CompensationOptions {
  OrientationMode mode{OrientationMode::kKeep};
  int grid{24};  ///< ψ samples over [−180°, 180°) for the DP (NLopt refines ±1 step)
  double wrist_margin{10.0 * kDeg};    ///< |θ5| ≥ margin (controller convention)
  double jump_threshold{60.0 * kDeg};  ///< max |Δθ4|, |Δθ6| between consecutive holes
  bool allow_branch_change{false};
  double limit_margin{10.0 * kDeg};  ///< penalty zone near joint limits
  bool refine{true};                 ///< NLopt refinement after the DP
  /// Worker threads over holes (≥ 1). The result is byte-identical for every count: sequential
  /// passes fix what carries from hole to hole (the IK seeds, the ψ sequence of the DP, each
  /// refinement against its refined predecessor), the per-hole work (candidate IK, NLopt, exact
  /// command, re-prediction) runs on the workers with per-thread scratch.
  int threads{1};
  /// Holes held at a time (≥ 1): each block of holes is predicted, finished and handed over in
  /// turn; flip-free and stiffest also evaluate their candidate grids a block at a time. The
  /// result is the same for every size (tests make it small).
  std::size_t block{kCompensationBlock};
  /// flip-free and stiffest: a run of holes whose programmed rotation (ψ = 0) is provably the
  /// sequence's choice evaluates that candidate alone, not its grid (flip-free: fewer changes;
  /// stiffest: a bound on how much a rotation can gain, see compensation.cpp). Off: every grid
  /// is evaluated — the same result (tests compare), more candidates (dp_nodes).
  bool skip_proven_grids{true};
};

/// What compensateTarget computes beyond the compensated target.
enum class TargetBudgets {
  kBoth,  ///< `before` and `after` are full predictions (budgets, verdicts): compensateHoles'
          ///< result
  /// `before` holds the IK choice only (chooseHoleSolution), `after` is not predicted, and the
  /// flags written are the command's own (the program's are not searched: a host's target has
  /// none); T_programmed, theta_cmd and the residual are compensateHoles' keep result
  kNone
};

/// Inline message capacities (bytes; inline_text.hpp: a longer text ends in "..."). The note is one
/// fixed 78-byte phrase; a ψ reason ≤ 110 bytes of phrase + one hole id (ids up to 146 bytes fit);
/// a flag reason ≤ 125 bytes of phrase + the program's flags + the mismatch of ≤ 6 turn flags
/// (≤ 50 bytes each) or the IK failure.
inline constexpr std::size_t kNoteChars = 128;
inline constexpr std::size_t kPsiReasonChars = 256;
inline constexpr std::size_t kConfigReasonChars = 512;
using NoteText = InlineText<kNoteChars>;
using PsiReasonText = InlineText<kPsiReasonChars>;
using ConfigReasonText = InlineText<kConfigReasonChars>;

/// One hole's result. Building it allocates nothing per hole: the messages are inline
/// texts (the capacities above), the budgets inline
/// (kMaxBudgetTerms); id, reason and the flag texts are std::string, within the short-string
/// buffer (15 bytes) for ids like the samples' and every vendor's flag text; reason is set only
/// for a hole that is not compensated.
struct HoleCompensation {
  std::string id;
  bool ok{false};
  std::string reason;
  HolePrediction before;                ///< prediction of the original target
  double psi{0.0};                      ///< rotation about the drill axis, rad
  Pose T_nominal{Pose::Identity()};     ///< T_nom · Rz(ψ), base frame
  Pose T_programmed{Pose::Identity()};  ///< TCP pose to program, base frame
  Pose delta{Pose::Identity()};         ///< ΔT = T_programmed · T_nominal⁻¹ (base frame)
  Vec6 theta_d{Vec6::Zero()};           ///< link-side joints at the nominal hole
  Vec6 theta_cmd{Vec6::Zero()};         ///< programmed joints (motor side, controller command)
  VendorConfig config;                  ///< flags written for the compensated target
  std::string config_text;              ///< formatConfig(config)
  std::string config_before;      ///< the program's flags (else those of the programmed posture)
  bool config_in_program{false};  ///< the program states flags at this hole (the writer edits them)
  bool config_changed{false};     ///< config_text ≠ config_before
  ConfigReasonText config_reason;  ///< why the flags changed ("" when kept)
  int branch{0};
  bool branch_changed{false};
  PsiReasonText psi_reason;  ///< why ψ ≠ 0 ("" when the programmed rotation is kept)
  /// stiffest: U_work (exact, m) of the keep compensation at this hole, NaN when not computed;
  /// the gain is U_work_keep − after.U_work_exact.
  double U_work_keep{std::numeric_limits<double>::quiet_NaN()};
  Vec3 residual{Vec3::Zero()};  ///< predicted real − nominal TCP position after compensation, m
  double residual_rot{0.0};     ///< rad
  HolePrediction after;         ///< budget at the compensated pose (U_work, verdict)
  NoteText note;                ///< e.g. the wrist margin could not be met at this hole
};

struct CompensationStats {
  int dp_nodes{0};  ///< candidates evaluated for the DP (skip_proven_grids: runs that keep ψ = 0)
  int infeasible_nodes{0};
  int refined{0};
  int nlopt_evaluations{0};
  bool relaxed_jumps{false};        ///< no path met the jump threshold; it was relaxed
  double jump_threshold_used{0.0};  ///< rad, the threshold the sequence meets
  int relaxed_wrist{0};  ///< holes where no rotation met |θ5| ≥ margin (kept as a penalty)
  // rotations about the drill axis (ψ ≠ 0) by reason
  int psi_changed{0};
  int psi_for_limits{0};     ///< ψ = 0 leaves the joint limits (or is singular / unreachable)
  int psi_for_wrist{0};      ///< ψ = 0 violates |θ5| ≥ margin
  int psi_for_jumps{0};      ///< ψ = 0 would make an axis-4/6 jump over the threshold
  int psi_for_stiffness{0};  ///< stiffest: ψ ≠ 0 is stiffer
  int config_changed{0};     ///< holes whose written flags change (program states flags)
  // stiffest: U_work gained over keep (holes where both were computed)
  int stiffness_compared{0};
  double U_work_keep_sum{0.0};  ///< m
  double U_work_sum{0.0};       ///< m
  double U_work_gain_max{0.0};  ///< m (largest per-hole gain)
};

/// Compensates a program's holes in sequence. With drills of their own TCP (drill_models), each
/// run of consecutive holes drilled at one TCP is a sequence of its own with its drill's model,
/// seeded with the last admissible joints before it: a tool change is a repositioning move, so
/// no jump limit applies across it.
std::vector<HoleCompensation> compensateHoles(const PredictionModel& m,
                                              const std::vector<HoleRequest>& holes,
                                              const CompensationOptions& options,
                                              CompensationStats* stats = nullptr);

/// Receives the compensated holes a block at a time, in hole order: `holes[k]` is hole
/// `first + k` of the request list. The holes may be moved from; they are dropped after the call.
using CompensationSink = std::function<void(std::size_t first, std::span<HoleCompensation> holes)>;

/// compensateHoles with the results handed to `sink` block by block instead of returned (the same
/// holes, bytes and statistics). keep holds a few blocks of results at a time (each block of holes
/// is predicted, compensated and handed over in turn, with workers up to two blocks ahead of the
/// sink); flip-free and stiffest choose the sequence over the whole program first (predictions and
/// grids a block at a time, the DP's predecessor table and chosen candidates for the program),
/// then predict again, finish and hand over the holes a block at a time (as keep).
void compensateHoles(const PredictionModel& m, const std::vector<HoleRequest>& holes,
                     const CompensationOptions& options, const CompensationSink& sink,
                     CompensationStats* stats = nullptr);

/// One target compensated with its orientation kept (the `keep` mode of compensateHoles for a
/// program of this one hole: the same T_programmed and theta_cmd, bit for bit) into `out`,
/// reusing `d` (a host's per-target call). `budgets` kNone skips the uncertainty budgets before
/// and after, the verdict and the search for the program's flags (a caller that needs only the
/// target to program). options.mode is ignored (keep).
void compensateTarget(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                      const CompensationOptions& options, TargetBudgets budgets,
                      HoleCompensation& out);

}  // namespace roprec
