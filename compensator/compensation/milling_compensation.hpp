#pragma once
/// \file milling_compensation.hpp
/// Compensation of a milling path: every path point's target is pre-offset so that
/// the predicted real tool lands on the nominal path under the milling force, which itself depends
/// on the deviation (docs/process.md §4.3–4.4). Per point i, in path order:
///   1. θ_d = IK(T_nom,i) (continuity from the previous point);
///   2. fixed point on the force F = Φ(F): θ_m(F) = θ_d + K⁻¹τ(θ_d; F) (exact inverse); Φ(F) is
///      the converged force of the coupled iteration of milling.hpp with the compensated robot's
///      compliance at θ_m(F) (δ(G) = real − nominal tool position under G, milling frame) from the
///      previous point's state. Solved from F⁽⁰⁾ = the previous point's converged force (same
///      cut; else F(fz, ae) nominal) by Broyden's method on r(F) = Φ(F) − F
///      (solveForceFixedPoint, its Jacobian estimate carried from point to point)
///      until |r| ≤ 1e-9 N — with an exact compensation the
///      tool stays on the path, the chip is nominal and this converges at the first check; the
///      plain iteration F ← Φ(F) diverges when the previous-edge coupling is strong (a tooth pass
///      or so between points: ∂Φ/∂F has a spectral radius above 1);
///   3. programmed target = rigid FK(θ_m); the residual is re-predicted with the converged force.
/// Non-convergence (coupling or force fixed point) is reported per point, never silently emitted.
///
/// Tooth passes between points (the feed term of milling.hpp): per point, the program's spacing
/// |p_i − p_{i−1}| / fz rounded, at least 1 (the first point: the cell's value), unless the cell's
/// <coupling> gives teeth_between_points or point_spacing_mm (then that value everywhere).
///
/// Engagement along the real path (box stock, docs/process.md §4.5): each chain keeps its own
/// EngagementTracker. The uncompensated chain queries the move into a point where the tool is
/// before the cut's own deflection (the path point + its deviation without the milling force:
/// the coupling adds the cut's deflection, Eq. 9) and records the move where the tool really went
/// (path point + deviation_before): a pass cuts what the earlier passes really left, so their
/// surface error changes its ae and ap (and can make a nominally idle pass cut). The compensated
/// chain queries at the path point (its coupling's δ is the whole deviation from it) and records
/// the compensated tool (path point + residual); where its engagement differs from the first
/// chain's, it couples with its own cut.
///
/// Cutting decision (docs/process.md §4.5): a point gets a milling force only if it cuts —
///   1. its move is not rapid: programmed linear speed ≤ kRapidSpeedFactor · vf, vf = fz Nt n/60
///      (unknown speed: not decided by speed);
///   2. the tool is at the cutting depth: with <stock top_z_mm>, depth = top_z − z_tcp (workobject
///      frame) ≥ ap − kDepthTolerance; without it, |z_tcp − z_ref| ≤ kDepthTolerance where z_ref is
///      the tool height at the first non-rapid linear point. With a box stock (<stock box_min_mm
///      box_max_mm>) instead: the move ending at the point engages material of the box not removed
///      by the program's earlier moves (milling_engagement.hpp), and that point is coupled with its
///      own ae and ap (the cell's ae/ap are then only the nominal of the report).
/// A non-cutting point is compensated for gravity and the tool weight only (force 0) and resets
/// the coupling's memory (the tool left the material).
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"
#include "compensator/process/milling_engagement.hpp"

namespace roprec {

/// A linear move faster than this × the feed speed vf is rapid (does not cut).
constexpr double kRapidSpeedFactor = 1.5;
/// "At the cutting depth" tolerance [m].
constexpr double kDepthTolerance = 0.1e-3;
/// A path point reuses the previous point's resolved revolution while its fz_eff, ae_eff and
/// ap_eff are within this of those it was computed with [m] (and the modes within 0.5 %).
constexpr double kEdgeReuseTolerance = 0.1e-6;

struct MillingPathPoint {
  Pose T_W_tcp{Pose::Identity()};  ///< nominal TCP, base frame
  double speed{-1.0};              ///< programmed linear speed [m/s]; < 0 unknown
};
struct CuttingDecision {
  bool cutting{true};
  std::string reason;  ///< why (speeds in mm/s, depths in mm)
  /// With a box stock: the engagement of the move ending at the point on the programmed path
  /// (milling_engagement.hpp); the point cuts when the move is not rapid and engages material
  /// (rule 2 is replaced). The chains re-decide it on their real paths.
  std::optional<MillingEngagement> engagement;
  bool rapid{false};  ///< rule 1: a rapid move (breaks the chain of moves of the engagement)
};
/// The cutting decision of every point (rules above). `T_W_wobj`: the cell's workobject.
std::vector<CuttingDecision> decideCutting(const MillingSpec& s, const Pose& T_W_wobj,
                                           const std::vector<MillingPathPoint>& points);
/// decideCutting one point at a time, in path order (a path read block by block): the same
/// decisions, with what the rules carry from point to point (the first feed move's height, the
/// box stock's material removed by the earlier moves).
class CuttingDecider {
 public:
  CuttingDecider(const MillingSpec& s, const Pose& T_W_wobj);
  /// The decision of the path's next point.
  CuttingDecision operator()(const MillingPathPoint& p);

 private:
  MillingSpec s_;
  Pose T_wobj_W_;
  std::optional<EngagementTracker> tracker_;
  std::optional<Vec3> prev_tip_;
  std::optional<double> z_ref_;
};

struct PathPointCompensation {
  bool ok{false};
  std::string reason;
  bool cutting{true};
  std::string cutting_reason;
  /// The engagement the uncompensated coupling used [m] (cutting points): the cell's, or with a
  /// box stock the real path's (earlier passes where the uncompensated tool really went).
  double ae{0}, ap{0};
  /// The compensated chain's: cutting, and the engagement its coupling used [m] (with a box stock
  /// its own real path's: the earlier passes where the compensated tool really went).
  bool cutting_after{true};
  double ae_after{0}, ap_after{0};
  Vec6 theta_d{Vec6::Zero()};
  Vec6 theta_cmd{Vec6::Zero()};
  Pose T_programmed{Pose::Identity()};
  Vec3 deviation_before{Vec3::Zero()};  ///< m, base frame, uncompensated (coupled force)
  /// m, base frame, uncompensated without the milling force (box stock, not rapid: where the
  /// engagement was queried, path point + this; else zero)
  Vec3 deviation_free{Vec3::Zero()};
  Vec3 residual{Vec3::Zero()};  ///< m, base frame, after compensation
  Vec3 force{Vec3::Zero()};     ///< converged force on the tool, milling frame, N
  int force_iterations{0};
  int coupling_iterations{0};
  bool coupling_converged{false};
  /// The uncompensated robot's coupled solve (the "before" deviation): the real test of the solver.
  /// Warm-started (milling.hpp CouplingOptions::start) from the previous point's δ and G while
  /// the previous point cut with the same cut and converged; else cold.
  std::string before_status;  ///< couplingStatusName, or "not_cutting"
  int before_iterations{0};
  double before_residual{0};  ///< |δ − C(F(δ))| [m]
  double before_loop_gain{0};
  Vec3 before_force{Vec3::Zero()};  ///< N, milling frame
  std::string coupling_status;      ///< couplingStatusName, or "not_cutting"
  double coupling_residual{0};      ///< |δ − C(F(δ))| of the final coupling [m]
  double loop_gain{0};              ///< of the final coupling
  std::string config_text;
  /// Chatter stability at the point (cutting points; milling_stability.hpp): the zero-order limit
  /// with the robot's modes at θ_d and the spindle/tool mode, at the cut's spindle speed; the
  /// previous point's limit is reused while every mode's frequency and TCP vector stay within
  /// 0.5 % of those it was computed with.
  bool stability_checked{false};
  bool stability_bounded{false};  ///< false: no chatter frequency found (stable at any depth)
  double ap_limit{0};             ///< limiting axial depth [m] (when bounded)
  double chatter_hz{0};           ///< chatter frequency at the limit [Hz]
  double first_mode_hz{0};        ///< the robot's first natural frequency at θ_d [Hz]
  /// The revolution resolved by edge angle at the uncompensated coupled cut (fz_eff, ae_eff,
  /// ap_eff of the "before" solve; milling.hpp edgeRevolution with the robot's modes at θ_d and
  /// the spindle/tool mode, 120 samples per tooth): each edge cuts what the previous edges left
  /// while the tool vibrates. Reused from the previous point while the modes stay within 0.5 %
  /// (as the stability) and fz_eff, ae_eff, ap_eff within kEdgeReuseTolerance of those it was
  /// computed with.
  /// Mode-coupling chatter of the modes at θ_d (milling_mode_coupling.hpp): the process
  /// stiffness of the point's cut through the robot's and the tool's modes; reused with the
  /// stability's cache rule.
  bool mode_coupling_checked{false};
  bool mode_coupling_bounded{false};  ///< false: stable up to 100 × ap
  double mode_coupling_ap_limit{0};   ///< [m] (when bounded)
  double mode_coupling_hz{0};         ///< frequency of the root crossing at the limit [Hz]
  bool mode_coupling_flutter{false};  ///< that root is a complex pair (else: static divergence)
  /// Tooth passes between the previous path point and this one that the feed term uses (the
  /// cell's teeth_between_points or point_spacing_mm / fz when it gives one, else the program's
  /// spacing / fz: teeth_from_cell says which).
  double teeth_between_points{0};
  bool teeth_from_cell{false};
  double before_fz_effective{0};  ///< fz_eff of the uncompensated solve [m]
  /// The deviation normal to the wall, + into the material (an overcut), [m]: the surface error
  /// a machinist measures. Before: the uncompensated tool; after: the predicted residual.
  double surface_error_before{0};
  double surface_error{0};
  bool edges_checked{false};
  bool edges_converged{false};
  std::vector<double> tooth_feed;   ///< chip-area feed per tooth [m]
  double peak_xy_nominal{0};        ///< rigid tool at the programmed cut [N]
  double peak_xy{0};                ///< at the coupled cut, vibrating tool [N]
  Vec3 vibration_pp{Vec3::Zero()};  ///< per axis max − min of the vibration [m]
  [[nodiscard]] bool regenerativeUnstable(double depth) const {
    return stability_checked && stability_bounded && ap_limit <= depth;
  }
  [[nodiscard]] bool modeCouplingUnstable(double depth) const {
    return mode_coupling_checked && mode_coupling_bounded && mode_coupling_ap_limit <= depth;
  }
  /// Chatter by either mechanism.
  [[nodiscard]] bool unstable(double depth) const {
    return regenerativeUnstable(depth) || modeCouplingUnstable(depth);
  }
};

/// The update of the compensated force fixed point F = Φ(F).
enum class ForceUpdate {
  kBroyden,  ///< Broyden's method on r(F) = Φ(F) − F (first step: the plain one), halving a step
             ///< whose Φ cannot be evaluated (default)
  kPlain,    ///< F ← Φ(F) (diverges when ∂Φ/∂F has a spectral radius above 1)
};
struct ForceFixedPoint {
  Vec3 force{Vec3::Zero()};  ///< Φ(F) at the last evaluated F (the fixed point when converged)
  int evaluations{0};        ///< of Φ
  bool converged{false};     ///< |Φ(F) − F| ≤ tolerance
  bool map_failed{false};    ///< Φ could not be evaluated (its last call returned false)
};
/// Solves F = Φ(F) from F0. `phi(F, out)` returns false when Φ cannot be evaluated at F.
/// `jacobian` (Broyden): the initial estimate of ∂(Φ(F) − F)/∂F (none: −I, the first step then
/// the plain one), and on return the updated estimate (a path warm-starts each point with the
/// previous point's: Φ changes little from point to point).
ForceFixedPoint solveForceFixedPoint(const std::function<bool(const Vec3&, Vec3&)>& phi,
                                     const Vec3& F0, ForceUpdate update, double tolerance = 1e-9,
                                     int max_evaluations = 20, Mat3* jacobian = nullptr);

/// What compensateMillingPath computes beyond the compensation, and on how many workers.
struct MillingPathOptions {
  /// Resolve the revolution by edge angle at every cutting point (the `edges_*`, `tooth_feed`,
  /// `peak_xy*` and `vibration_pp` fields); a caller that reports none of them (compensate)
  /// leaves it off: nothing else depends on it.
  bool resolve_edges{true};
  /// Workers (>= 1): the uncompensated chain (IK, "before" coupling, modes, chatter) and the
  /// compensated chain of each block of points run as a pipeline, the revolutions of a block
  /// on the workers; the results are the same whatever the count.
  int threads{1};
  /// Points per block of the pipeline (>= 1).
  size_t block{512};
  /// The stock's (workobject) frame in the base frame: where a box stock is (the engagement of
  /// the real paths).
  Pose T_W_stock{Pose::Identity()};
  /// The compensated force fixed point's update (kPlain only to compare).
  ForceUpdate force_update{ForceUpdate::kBroyden};
};

/// `m` must carry a milling process. Points are nominal TCP poses in the base frame (path order);
/// `cutting` (optional, one per point) says which points cut — all of them when absent. The first
/// point's IK is seeded with `seed` (rad), else the model's reference pose.
std::vector<PathPointCompensation> compensateMillingPath(
    const PredictionModel& m, const std::vector<Pose>& points,
    const std::vector<CuttingDecision>* cutting = nullptr, const Vec6* seed = nullptr,
    const MillingPathOptions& options = {});

/// Receives the results of points [first, first + block.size()) — blocks of options.block points,
/// in path order, each once — and may move from them: they are not kept after the call (a path's
/// results are never all in memory at once).
using MillingPathSink =
    std::function<void(std::size_t first, std::span<PathPointCompensation> block)>;
/// compensateMillingPath handing each block of results to `sink` as soon as both chains are done
/// with it (on the calling thread, while the compensated chain runs over the next block); the
/// same results, bit for bit, whatever options.block and options.threads.
void compensateMillingPath(const PredictionModel& m, const std::vector<Pose>& points,
                           const std::vector<CuttingDecision>* cutting, const Vec6* seed,
                           const MillingPathOptions& options, const MillingPathSink& sink);

/// Gives the path's next points, in path order: appends up to `count` nominal TCP poses (base
/// frame) to `points` and, for a path with cutting decisions, as many decisions to `cutting`;
/// returns how many (fewer than `count`: the path ends with them).
using MillingPathSource = std::function<std::size_t(std::size_t count, std::vector<Pose>& points,
                                                    std::vector<CuttingDecision>& cutting)>;
/// compensateMillingPath of a path read block by block from `source` (blocks of options.block
/// points; two of them held at a time: memory does not grow with the path). `with_cutting`: the
/// source gives every point's cutting decision (else every point cuts). The same results, bit for
/// bit, as the path read whole.
void compensateMillingPath(const PredictionModel& m, const MillingPathSource& source,
                           bool with_cutting, const Vec6* seed, const MillingPathOptions& options,
                           const MillingPathSink& sink);

}  // namespace roprec
