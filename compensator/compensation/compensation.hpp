#pragma once
/// \file compensation.hpp
/// Pre-offsetting drill targets so that the predicted real hole lands on the nominal one, and
/// choosing the free rotation ψ about each drill axis (NLopt + dynamic programming).
///
/// Per hole, for a rotation ψ about the drill axis and an IK branch:
///   1. desired TCP  T_d = T_nom · Rz(ψ); link-side joints θ_d = IK(T_d) in the branch;
///   2. motor-side command θ_m = θ_d + K_eff⁻¹ τ(θ_d) — exact, the inverse of deflection.hpp
///      (τ with link/tool weight and the process wrench following the real = desired tool axis);
///      a controller that compensates gravity itself adds its own offset, which is removed here;
///   3. programmed target = the controller's rigid FK of θ_m, with the configuration flags of θ_m.
/// Every target of a drill cycle moves with the drill point (T ← ΔT · T · Rz(ψ), ΔT = T_prog T_d⁻¹)
/// so the drilling axis stays straight. Re-predicting the programmed pose gives θ = θ_d exactly
/// (to the equilibrium tolerance), hence a systematic residual at solver precision.
///
/// Orientation modes (`--orientation`):
///   keep       ψ = 0 and positions only: the programmed orientation is the original one to the
///              last bit; the programmed position is iterated until the predicted real TCP
///              position is the nominal one (the real drill axis keeps its small tilt);
///   flip-free  minimise joint travel between consecutive holes with penalties near joint limits
///              and the wrist singularity, subject to |θ5| ≥ margin, |Δθ4|, |Δθ6| ≤ threshold
///              between consecutive holes of one face (axes within 10°; a face change is a
///              repositioning move) and the same IK branch (unless a change is allowed);
///   stiffest   minimise the predicted U_work (stiffness) under the same constraints.
/// Sequence level: dynamic programming over a discretised ψ grid for the whole program (not hole
/// by hole), then NLopt (COBYLA, 1-D, constraints as above) refines each hole's ψ with its
/// neighbours fixed.

#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"

namespace roprec {

enum class OrientationMode { kKeep, kFlipFree, kStiffest };
const char* orientationModeName(OrientationMode m);

struct CompensationOptions {
  OrientationMode mode{OrientationMode::kKeep};
  int grid{24};  ///< ψ samples over [−180°, 180°) for the DP (NLopt refines ±1 step)
  double wrist_margin{10.0 * kDeg};    ///< |θ5| ≥ margin (controller convention)
  double jump_threshold{60.0 * kDeg};  ///< max |Δθ4|, |Δθ6| between consecutive holes
  bool allow_branch_change{false};
  double limit_margin{10.0 * kDeg};  ///< penalty zone near joint limits
  bool refine{true};                 ///< NLopt refinement after the DP
};

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
  VendorConfig config;
  std::string config_text;
  int branch{0};
  bool branch_changed{false};
  Vec3 residual{Vec3::Zero()};  ///< predicted real − nominal TCP position after compensation, m
  double residual_rot{0.0};     ///< rad
  HolePrediction after;         ///< budget at the compensated pose (U_work, verdict)
  std::string note;             ///< e.g. the wrist margin could not be met at this hole
};

struct CompensationStats {
  int dp_nodes{0};
  int infeasible_nodes{0};
  int refined{0};
  int nlopt_evaluations{0};
  bool relaxed_jumps{false};  ///< no path met the jump threshold; it was relaxed
  int relaxed_wrist{0};       ///< holes where no rotation met |θ5| ≥ margin (kept as a penalty)
};

std::vector<HoleCompensation> compensateHoles(const PredictionModel& m,
                                              const std::vector<HoleRequest>& holes,
                                              const CompensationOptions& options,
                                              CompensationStats* stats = nullptr);

}  // namespace roprec
