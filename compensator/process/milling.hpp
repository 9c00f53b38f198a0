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
///   fz_i = fz + (δ_i − δ_{i−1})·X / n_teeth + δprev_i,   ae_i = ae + δ_i·n_wall
/// (n_wall = +Y up-milling, −Y down-milling, 0 for a slot), F_i = F̄(fz_i, ae_i), δ_i = C_i(F_i),
/// iterated until |δ^(k+1) − δ^(k)| ≤ tolerance (default 0.1 µm). δprev carries a negative chip
/// (the tooth did not reach the surface) to the next point. The loop gain (spectral radius of
/// ∂(C∘F)/∂δ) is reported; ≥ 1 means the plain iteration cannot converge (optional under-relaxation
/// ω).

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "compensator/process/materials.hpp"
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
///   kInstantaneous: exact average of the instantaneous Kienzle law, Nt/(2π)∫ Ft(fz sin φ)(…) dφ
///                   (Gauss–Legendre over the arc; equals the mean of millingForceProfile without
///                   runout);
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

/// Tool deflection [m] under a force on the tool [N], both in the milling frame (the robot's
/// compliance at this path point; later wired to the robot deflection model).
using ComplianceFunction = std::function<Vec3(const Vec3& force_N)>;
ComplianceFunction linearCompliance(const Mat3& C_m_per_N);

struct CouplingOptions {
  double tolerance{0.1e-6};  ///< stop when |δ^(k+1) − δ^(k)| ≤ this [m]
  int max_iterations{50};
  double relaxation{1.0};  ///< ω in (0, 1]: δ ← (1−ω)δ + ω C(F)
  /// Tooth passes between successive path points: the feed-direction deflection change per
  /// tooth is (δ_i − δ_{i−1})·X / n. Default 10 (path points 1 mm apart at fz 0.1 mm).
  int teeth_between_points{10};
};

struct CouplingState {
  Vec3 delta_prev{Vec3::Zero()};  ///< converged δ at the previous path point [m]
  double uncut_prev{0.0};         ///< δprev: negative chip carried from the previous edge [m]
};

enum class CouplingStatus { kConverged, kDiverged, kMaxIterations, kOutOfRange };
const char* couplingStatusName(CouplingStatus s);

struct CouplingResult {
  bool converged{false};
  CouplingStatus status{CouplingStatus::kMaxIterations};
  int iterations{0};
  double residual{0};  ///< last |δ^(k+1) − δ^(k)| [m]
  double loop_gain{0};  ///< spectral radius of ∂(C∘F)/∂δ, max of the first and the final iterate
  Vec3 delta{Vec3::Zero()};  ///< converged tool deflection [m]
  Vec3 force{Vec3::Zero()};  ///< force on the tool at δ [N]
  Vec3 force_nominal{Vec3::Zero()};
  double fz_effective{0};  ///< [m]
  double ae_effective{0};  ///< [m]
  CouplingState next;      ///< state to pass to the next path point
};

/// One path point: fixed-point iteration of δ = C(F(fz_i(δ), ae_i(δ))).
CouplingResult coupleMillingPoint(const MillingModel& m, const ComplianceFunction& compliance,
                                  const CouplingState& state, const CouplingOptions& options = {});

/// A path: compliance per point (e.g. the robot's C(q_i)); the state is carried point to point.
std::vector<CouplingResult> coupleMillingPath(
    const MillingModel& m, const std::vector<ComplianceFunction>& compliance_per_point,
    const CouplingOptions& options = {});

}  // namespace roprec
