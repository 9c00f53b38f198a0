#pragma once
/// \file milling.hpp
/// Peripheral end milling (docs/process.md §4) and its static coupling with the robot (§4.4).
///
/// Milling frame (Altintas convention): X = feed direction; the immersion angle φ is measured
/// clockwise from +Y (radial unit n(φ) = (sin φ, cos φ, 0)); Z points from the tool tip toward the
/// spindle, and the cutter turns clockwise seen from the spindle. (The drilling tool frame has z
/// into the material, i.e. z_tool = −Z.)
///
/// Entry/exit [§4.1]: up-milling φst = 0, φex = acos(1 − 2ae/D); down-milling φst = π − acos(1 −
/// 2ae/D), φex = π; slot (ae ≥ D) 0 → π; φpr = φex − φst. Mean chip thickness: h_m = fz (cos φst −
/// cos φex)/(φex − φst) = 2 fz (ae/D)/acos(1 − 2ae/D) (→ 2fz/π slot). Kienzle per tooth
/// (instantaneous): dFt = kc1.1 dz h0 (h/h0)^(1−mc) (h0 = 1 mm), dFr = cr dFt, dFa = ca dFt; on the
/// tool: Fx = −Ft cos φ − Fr sin φ, Fy = Ft sin φ − Fr cos φ, Fz = −Fa (a right-hand helix pulls
/// the tool toward the tip). Runout (Kline & DeVor 1983): R_j = R + ρ cos(λ − j·2π/Nt), j =
/// 0..Nt−1. Chip thickness with memory of all earlier teeth (§4.3):
///   h_j(φ,t) = max{0, min_{k=1..Nt} [k fz sin φ + (R_j − R_{j−k}) + (δ(t) − δ(t − kτ))·n(φ)]}
/// — the min over k is what the previous edges did not cut.
/// Helix: the edge at height z lags ψ(z) = z tan β / R.
///
/// Revolution-averaged forces from h_m (used by the coupling, §4.4 "recompute from h_m directly"):
///   F̄t = Nt φpr/(2π) kc1.1 ap h0 (h_m/h0)^(1−mc); with Ft,m = kc1.1 ap h0 (h_m/h0)^(1−mc),
///   F̄x = Nt Ft,m/(2π) [−(sin φex − sin φst) − cr (cos φst − cos φex)],
///   F̄y = Nt Ft,m/(2π) [(cos φst − cos φex) − cr (sin φex − sin φst)],  F̄z = −ca F̄t.
///
/// Coupling per path point i (§4.3/§4.4): with tool deflection δ (milling frame, m),
///   fz_i(δ) = fz + (δ − δ_{i−1})·X / n_teeth + δprev_i,   ae_i(δ) = ae + δ·n_wall,
///   ap_i(δ) = ap − δ·Z
/// (n_wall = +Y up-milling, −Y down-milling, 0 for a slot; +Z lifts the tool out of the cut),
/// F_i(δ) = F̄(fz_i, ae_i)·ap_i/ap (F̄ is linear in ap), and the coupled residual
///   r(δ) = δ − C_i(F_i(δ)),   solved for r(δ) = 0.
/// Default solver (CouplingMethod::kNewton): Newton on r with a forward-difference Jacobian
/// J = I − G, G = ∂(C∘F)/∂δ (step 1 µm), and a backtracking line search on |r| (Armijo, α halved
/// down to 2⁻³⁰); it converges whatever the loop gain ρ(G). Convergence: |r(δ)| ≤ tolerance
/// (default 0.1 µm) — the residual of the equation itself, not the last step. Not converged is a
/// status (never a throw): no descent (|r| has no zero near: no fixed point), iteration limit,
/// the fixed point leaves the cut's range (ae > D, fz_eff > 0.2 D or ap_eff > 2 ap), or the
/// compliance failed (its equilibrium did not converge). CouplingMethod::kFixedPoint keeps the
/// plain (optionally under-relaxed) iteration δ ← (1−ω)δ + ω C(F(δ)), which converges only for ρ(G)
/// < 1 (for comparison). δprev carries a negative chip (the tooth did not reach the surface) to the
/// next point. The loop gain ρ(G) at the solution is reported.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compensator/process/materials.hpp"
#include "compensator/process/milling_dynamics.hpp"
#include "compensator/support/rotation.hpp"

namespace roprec {

enum class MillingMode { kUp, kDown, kSlot };

struct MillingTool {
  double diameter{10e-3};         ///< D [m]
  int teeth{3};                   ///< Nt
  double helix_angle{30 * kDeg};  ///< β [rad]
  double runout{0.0};             ///< ρ [m]
  double runout_angle{0.0};       ///< λ, locating angle of the runout [rad]
};

struct MillingCut {
  double ap{5e-3};    ///< axial depth [m]
  double ae{2e-3};    ///< radial depth [m]
  double fz{0.1e-3};  ///< feed per tooth [m]
  MillingMode mode{MillingMode::kUp};
  double spindle_rpm{10000};
};

struct ImmersionAngles {
  double start{0};  ///< φst [rad]
  double exit{0};   ///< φex [rad]
};
ImmersionAngles immersionAngles(double diameter, double ae, MillingMode mode);
/// h_m = fz (cos φst − cos φex)/(φex − φst) [m].
double meanChipThickness(double fz, const ImmersionAngles& a);

/// How the coupling recomputes the revolution-averaged force at (fz_i, ae_i):
///   kInstantaneous: exact average of the instantaneous Kienzle law, (1/2π) Σ_j ∫ Ft(h_j)(…) dφ
///                   with tooth j's chip h_j = min_k [k fz sin φ + R_j − R_{j−k}] (runout and
///                   the memory of the earlier teeth, §4.3), Gauss–Legendre over the part of the
///                   arc where h_j ≥ h_min (so that it is continuous in fz), split where the
///                   minimising k changes; equals the mean of millingForceProfile without helix;
///   kMeanChip:      the source paper's form with h_m (closed form in the file comment) [P].
enum class MeanForceLaw { kInstantaneous, kMeanChip };

struct MillingModel {
  MillingTool tool;
  MillingCut cut;
  MillingCoefficients coeff;
  int angle_steps{360};              ///< samples per revolution
  int slices{20};                    ///< axial slices
  std::vector<double> tooth_radius;  ///< R_j with runout [m]
  std::vector<double> slice_lag;     ///< ψ(z) at each slice centre [rad]
  double slice_height{0};            ///< dz [m]
  MeanForceLaw mean_law{MeanForceLaw::kInstantaneous};
  std::vector<double> gl_x, gl_w;  ///< Gauss–Legendre nodes on [−1, 1] for the arc average
};
MillingModel makeMillingModel(const MillingTool& tool, const MillingCut& cut,
                              const MillingCoefficients& c, int angle_steps = 360, int slices = 20);

/// Chip thickness of tooth j at immersion φ, with memory over k = 1..Nt earlier passes.
/// `deflection_history` (optional, Nt+1 entries): δ(t), δ(t−τ), …, δ(t−Nt τ) in the XY plane [m].
double toothChipThickness(const MillingModel& m, int tooth, double phi, double fz,
                          const Eigen::Vector2d* deflection_history = nullptr);

struct MillingSample {
  double angle{0};           ///< cutter rotation angle of tooth 0 [rad]
  Vec3 force{Vec3::Zero()};  ///< force on the tool, milling frame [N]
};
struct MillingProfile {
  std::vector<MillingSample> samples;  ///< one revolution
  Vec3 mean{Vec3::Zero()};             ///< revolution average [N]
  double peak_xy{0};                   ///< max |(Fx, Fy)| [N]
  std::vector<double> max_chip;        ///< per tooth, max chip thickness over the revolution [m]
};
/// Force vs cutter angle over one revolution (static, rigid tool, with runout and tooth memory).
MillingProfile millingForceProfile(const MillingModel& m);

/// Revolution-averaged force at (fz, ae) under model.mean_law [N], milling frame.
Vec3 millingMeanForce(const MillingModel& m, double fz, double ae);

/// millingMeanForce remembering the (fz, ae) it was last asked for (the 8 most recently used):
/// a path point's solves ask again for the same ones — the coupling's Jacobian column along Z
/// moves ap only (F̄ is linear in ap), its final image repeats the last accepted iterate, and
/// successive solves at one point (a force fixed point around them) start from the same cut.
/// Bound to one model: reset() it when the model changes. The same bits as millingMeanForce.
class MeanForceMemo {
 public:
  Vec3 operator()(const MillingModel& m, double fz, double ae);
  void reset();

 private:
  struct Entry {
    double fz{0}, ae{0};
    Vec3 F{Vec3::Zero()};
    unsigned long used{0};  ///< 0: empty
  };
  std::array<Entry, 8> entries_{};
  unsigned long clock_{0};
};

/// Tool deflection [m] under a force on the tool [N], both in the milling frame (the robot's
/// compliance at this path point; later wired to the robot deflection model).
using ComplianceFunction = std::function<Vec3(const Vec3& force_N)>;
ComplianceFunction linearCompliance(const Mat3& C_m_per_N);
/// The robot's compliance and the spindle/tool's static compliance in series: C(F) + C_tool F.
ComplianceFunction withToolCompliance(ComplianceFunction robot, const Mat3& C_tool);

enum class CouplingMethod {
  kNewton,      ///< Newton + line search on r(δ) = δ − C(F(δ)) (default)
  kFixedPoint,  ///< plain iteration δ ← (1−ω)δ + ω C(F(δ)) (converges only for loop gain < 1)
};
const char* couplingMethodName(CouplingMethod m);

struct CouplingOptions {
  double tolerance{0.1e-6};  ///< converged when |r(δ)| ≤ this (fixed point: |Δδ| ≤ this) [m]
  int max_iterations{50};
  double relaxation{1.0};  ///< fixed point only: ω in (0, 1], δ ← (1−ω)δ + ω C(F)
  CouplingMethod method{CouplingMethod::kNewton};
  /// Tooth passes between successive path points: the feed-direction deflection change per
  /// tooth is (δ_i − δ_{i−1})·X / n. Default 10 (path points 1 mm apart at fz 0.1 mm).
  int teeth_between_points{10};
  /// Compute CouplingResult::loop_gain at the solution (Newton: three more evaluations of the
  /// force law and the compliance); false leaves it 0 — a caller that solves a point several
  /// times reports it of the last solve only (couplingLoopGain).
  bool loop_gain{true};
  /// Warm start (Newton; a path's next point): the iteration starts at `start` (e.g. the
  /// previous point's δ) instead of C(F(0)), its steps use `start_gain` (G at a nearby δ, e.g.
  /// CouplingResult::gain of the previous point) instead of a finite-difference G while each
  /// lowers |r| tenfold (then finite-difference Newton), and it goes on until |r| <= tolerance /
  /// 10⁴ — below where a cold start's final full Newton step usually lands: along a path with
  /// few tooth passes between points the point-to-point memory carries each point's error on —
  /// or no step lowers |r| (converged if |r| <= tolerance). Both or neither (start without
  /// start_gain: the cold start).
  std::optional<Vec3> start;
  std::optional<Mat3> start_gain;
};

struct CouplingState {
  Vec3 delta_prev{Vec3::Zero()};  ///< converged δ at the previous path point [m]
  double uncut_prev{0.0};         ///< δprev: negative chip carried from the previous edge [m]
};

/// kNoDescent: the line search found no step that lowers |r| (no fixed point near: e.g. an
/// unphysical compliance); kOutOfRange: the fixed point has ae > D or fz_eff > 0.2 D (a runaway
/// positive feedback, e.g. down-milling on a feed-soft robot); kComplianceFailed: the
/// compliance threw (robot equilibrium not converged).
enum class CouplingStatus {
  kConverged,
  kDiverged,
  kMaxIterations,
  kOutOfRange,
  kNoDescent,
  kComplianceFailed
};
const char* couplingStatusName(CouplingStatus s);

struct CouplingResult {
  bool converged{false};
  CouplingStatus status{CouplingStatus::kMaxIterations};
  int iterations{0};         ///< Newton (or fixed-point) iterations
  int evaluations{0};        ///< calls of the compliance C
  double residual{0};        ///< |r(δ)| = |δ − C(F(δ))| at the returned δ [m]
  double step{0};            ///< last |Δδ| [m]
  double loop_gain{0};       ///< spectral radius of G = ∂(C∘F)/∂δ at the returned δ (fixed
                             ///< point: the larger of that and the gain at δ = 0)
  Vec3 delta{Vec3::Zero()};  ///< converged tool deflection [m]
  Vec3 force{Vec3::Zero()};  ///< force on the tool at δ [N]
  Vec3 force_nominal{Vec3::Zero()};
  double fz_effective{0};  ///< [m]
  double ae_effective{0};  ///< [m]
  double ap_effective{0};  ///< ap − δ·Z [m]
  CouplingState next;      ///< state to pass to the next path point
  /// G = ∂(C∘F)/∂δ at the returned δ when the solve computed it (Newton with options.loop_gain,
  /// or the plain iteration): a warm start for the next point (CouplingOptions::start_gain).
  std::optional<Mat3> gain;
};

/// One path point: solves δ = C(F(fz_i(δ), ae_i(δ))) with options.method. Never throws for a
/// failing compliance: the status says so. `memo` (optional, bound to `m`): the mean forces
/// remembered across calls (the result is the same with or without it).
CouplingResult coupleMillingPoint(const MillingModel& m, const ComplianceFunction& compliance,
                                  const CouplingState& state, const CouplingOptions& options = {},
                                  MeanForceMemo* memo = nullptr);

/// The loop gain coupleMillingPoint reports (with options.loop_gain) of a solve `r` made with
/// these arguments (Newton: the spectral radius of G at r.delta, 0 when that solve's compliance
/// failed; the plain iteration computes it always: r.loop_gain). The same bits as the solve's.
double couplingLoopGain(const MillingModel& m, const ComplianceFunction& compliance,
                        const CouplingState& state, const CouplingOptions& options,
                        const CouplingResult& r, MeanForceMemo* memo = nullptr);

/// A path: compliance per point (e.g. the robot's C(q_i)); the state is carried point to point.
std::vector<CouplingResult> coupleMillingPath(
    const MillingModel& m, const std::vector<ComplianceFunction>& compliance_per_point,
    const CouplingOptions& options = {});

/// ## The revolution resolved by edge angle (docs/process.md §4.5)
/// The steady periodic cut at a path point whose static cut is (fz, ae, ap), each edge cutting
/// what the previous edges left, with the tool vibrating under the cut it makes:
///   x(t) = Σ_{k≥1} 2 Re[H(kΩ) F̂_k e^{ikΩt}]   (the dynamic part; the static δ is the coupling's),
///   h_j(φ, t) = max{0, min_{k=1..Nt} [k fz sin φ + (R_j − R_{j−k}) + (x(t) − x(t − kτ))·n(φ)]},
///   ae(t) = ae + x(t)·n_wall,   ap(t) = ap − x(t)·Z,
/// F(t) = Σ_j Σ_slices (Kienzle law at h_j over the arc of ae(t), slice height ap(t)/slices) — the
/// same force law, runout and helix as millingForceProfile. τ = 2π/(Nt Ω) is the tooth period;
/// the revolution is sampled at N = Nt · samples_per_tooth cutter angles of tooth 0, so that the
/// earlier passes are whole sample shifts. The periodic x is the fixed point of x ↦ x_dyn(F(x)),
/// iterated with relaxation ω (halved, down to 1/64, whenever the update grows) until
/// max_n |Δx| ≤ tolerance. Without modes x = 0 and this is the rigid profile at (fz, ae, ap). A
/// regenerative loop too strong for the iteration (near or past the chatter limit; whether the cut
/// chatters is milling_stability's verdict) ends with converged = false and the last iterate,
/// never a throw or NaN: after max_iterations, or as soon as the update has grown
/// `diverging_iterations` times in a row at the smallest ω (the relaxed map itself expands: it
/// will not settle).
/// Per tooth, the effective feed is the chip-area equivalent
///   fz_j = Σ_{in cut} h_j / Σ_{static arc} sin φ  (over the revolution's angles and slices; the
///   denominator over the arc of ae, the same for every tooth),
/// which is fz for a rigid tool without runout. The teeth share the material: in steady state the
/// mean over the teeth is fz up to what the vibrating wall (ae(t)) adds or takes at the arc's
/// end, while each tooth's differs (runout, and the vibration between successive edges).
struct EdgeRevolutionOptions {
  int samples_per_tooth{120};
  double tolerance{1e-9};  ///< on max_n |Δx| [m]
  int max_iterations{300};
  double relaxation{1.0};  ///< initial ω
  int diverging_iterations{20};
};
struct EdgeRevolution {
  bool converged{false};
  int iterations{0};
  std::vector<double> angle;       ///< cutter angle of tooth 0 [rad]
  std::vector<Vec3> force;         ///< on the tool, milling frame [N]
  std::vector<Vec3> vibration;     ///< x_dyn [m], milling frame
  std::vector<double> tooth_feed;  ///< fz_j [m]
  std::vector<double> max_chip;    ///< per tooth [m]
  Vec3 mean{Vec3::Zero()};         ///< revolution average [N]
  double peak_xy{0};               ///< max |(Fx, Fy)| [N]
  double update{0};                ///< last max_n |Δx| [m]
};
EdgeRevolution edgeRevolution(const MillingModel& m, const ModalModel& dynamics, double fz,
                              double ae, double ap, const EdgeRevolutionOptions& options = {});

/// The corrected revolution at a coupled point (docs/process.md §4.5–4.6): per cutter angle of
/// tooth 0 (m.angle_steps rounded up to a multiple of Nt), the nominal force (rigid tool at the
/// programmed fz, ae, ap) and the corrected force: edgeRevolution at the coupled point's fz_eff,
/// ae_eff, ap_eff (the robot's static deflection and the previous edge's uncut chip δprev) with
/// the tool vibrating through `dynamics` (milling_dynamics.hpp: robot modes at the pose and the
/// spindle/tool mode) — each edge cuts what the previous edges left. The TCP movement is
///   x(φ) = δ + x_dyn(φ),
/// δ the coupled static deflection of the point (the mean force through the full compliance) and
/// x_dyn the periodic vibration of that regenerative steady state.
struct CorrectedSample {
  double angle{0};                  ///< [rad]
  Vec3 nominal{Vec3::Zero()};       ///< [N], milling frame
  Vec3 corrected{Vec3::Zero()};     ///< [N]
  Vec3 tcp_movement{Vec3::Zero()};  ///< [m]
};
struct CorrectedRevolution {
  std::vector<CorrectedSample> samples;
  EdgeRevolution nominal_edges;    ///< rigid tool at the programmed cut
  EdgeRevolution corrected_edges;  ///< vibrating tool at the coupled cut
  Vec3 mean_nominal{Vec3::Zero()}, mean_corrected{Vec3::Zero()};
  double peak_nominal_xy{0}, peak_corrected_xy{0};  ///< [N]
  double movement_range{0};  ///< max − min of |TCP movement| over the revolution [m]
  Vec3 vibration_peak_to_peak{Vec3::Zero()};  ///< per axis max − min of x_dyn [m]
};
CorrectedRevolution correctedRevolution(const MillingModel& m, const ModalModel& dynamics,
                                        const CouplingResult& point);

}  // namespace roprec
