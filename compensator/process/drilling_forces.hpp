#pragma once
/// \file drilling_forces.hpp
/// Mechanistic twist-drill forces (docs/process.md §2.1): specific pressures
///   kst = kst0 (at + bt γn + ct λs)(h/1 mm)^−m,  ksa = ksa0 (aa + ba γn + ca λs)(h/1 mm)^−m
/// integrated along each lip by Gauss–Legendre on [r_in, r_out] (a ≤ r_in < r_out ≤ R):
///   Ft,k = ∫ kst h dr/sin κr,  Fa,k = ∫ ksa h dr/sin κr,  Frad,k = ∫ ksa h dr/(sin κr tan κr),
///   M_k  = ∫ kst h r dr/sin κr,   h_k(r) = (f/2 + s_k 2ρ cot p) sin κr, s_1 = +1, s_2 = −1
/// (runout ρ: unequal lip chips, clipped at h_min; lip 1 alone cuts the annulus [R−ρ, R+ρ] at the
/// full feed). Thrust Fz = Σ Fa,k + F_ch (chisel, materials.hpp ChiselModel), torque M = Σ M_k +
/// M_ch. The in-plane residual (tangential + radial, summed vectorially over the lips) is the force
/// Fr that rotates with the spindle.
///
/// Progressive entry and breakthrough (§2.1) with the tip a depth z below the entry surface of a
/// plate of thickness T: r_out(z) = min{R, a + z tan p}; for a through hole and z > T the inner
/// limit is r_in(z) = a + (z − T) tan p and the chisel is out (thrust collapses before torque).
///
/// Wrench on the TCP, tool frame (z = drill axis into the material, spindle turns about +z):
///   force  = (Fr_x(φ), Fr_y(φ), −Fz)      — the workpiece pushes the drill back along −z;
///   torque = (0, 0, −M)                   — the cutting torque opposes the spindle rotation.
/// φ is the spindle angle (lip 1 on +x at φ = 0); the residual rotates with it.
///
/// Model/Data split: makeDrillingModel precomputes the Gauss nodes and per-node geometry (edge
/// frames built with quaternions, drill_geometry.hpp); drillingForces() then evaluates one hole
/// without allocation.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "compensator/process/drill_geometry.hpp"
#include "compensator/process/materials.hpp"

namespace roprec {

/// Per-node geometry of one lip (lip 1 at spindle angle 0; lip 2 is its 180° image).
struct EdgeNodes {
  std::vector<double> r;          ///< node radius [m]
  std::vector<double> weight;     ///< Gauss–Legendre weight on [r_in, r_out] [m]
  std::vector<double> g_t, g_a;   ///< geometry factors at + bt γn + ct |λs| (and axial), >= 0
  std::vector<double> sin_kappa;  ///< sin κr
  std::vector<double> cot_kappa;  ///< 1 / tan κr
  std::vector<double> sin_pow_t;  ///< (sin κr)^−m_t
  std::vector<double> sin_pow_a;  ///< (sin κr)^−m_a
  std::vector<double> vx, vy;     ///< in-plane cutting-velocity direction (unit)
  std::vector<double> erx, ery;   ///< radial direction
  void resize(int n);
};

struct DrillingModel {
  DrillGeometry geometry;
  DrillingCoefficients coeff;
  AngleLaw law{AngleLaw::kGeometric};
  double angle_feed{0.0};  ///< feed at which working angles were built [m/rev]; 0 = static angles
  int nodes{24};           ///< Gauss–Legendre nodes per lip
  EdgeNodes full;          ///< nodes on [a, R] (full engagement)
  double corner_sin_kappa{1}, corner_cot_kappa{0}, corner_g_t{1}, corner_g_a{1};
  Eigen::Vector2d corner_v{0, 1}, corner_er{1, 0};
  std::vector<double> gl_x, gl_w;  ///< Gauss–Legendre abscissae/weights on [−1, 1]
};

/// Evaluation buffers (partial engagement rebuilds the node table here).
struct DrillingData {
  EdgeNodes partial;
  explicit DrillingData(const DrillingModel& model);
};

/// Builds the model; `working_feed` > 0 uses working angles at that feed (geometric law).
DrillingModel makeDrillingModel(const DrillGeometry& g, const DrillingCoefficients& c,
                                AngleLaw law = AngleLaw::kGeometric, double working_feed = 0.0,
                                int nodes = 24);

struct LipForces {
  double Ft{0};    ///< tangential force of the lip [N]
  double Fa{0};    ///< axial force of the lip [N]
  double Frad{0};  ///< radial (edge-normal in-plane) force of the lip [N]
  double M{0};     ///< torque of the lip [N m]
};

struct DrillingForces {
  double thrust{0};                                      ///< Fz = Σ Fa,k + F_ch [N]
  double thrust_lips{0};                                 ///< Σ Fa,k [N]
  double thrust_chisel{0};                               ///< F_ch [N]
  double tangential{0};                                  ///< Σ Ft,k (scalar sum over lips) [N]
  double torque{0};                                      ///< M = Σ M_k + M_ch [N m]
  double torque_chisel{0};                               ///< M_ch [N m]
  double residual{0};                                    ///< |Fr|, rotating in-plane residual [N]
  Eigen::Vector2d residual_xy{Eigen::Vector2d::Zero()};  ///< Fr on the tool at spindle angle 0 [N]
  LipForces lip[2];
  double r_in{0}, r_out{0};  ///< engaged radii [m]
  bool chisel_engaged{true};
};

/// Force/torque that the workpiece exerts on the TCP, in the tool frame.
struct ToolWrench {
  Vec3 force{Vec3::Zero()};   ///< [N]
  Vec3 torque{Vec3::Zero()};  ///< [N m]
};
ToolWrench toolWrench(const DrillingForces& F, double spindle_angle = 0.0);

/// Steady (fully engaged) forces at feed f [m/rev]. No allocation.
DrillingForces drillingForces(const DrillingModel& model, double feed);

/// Forces with the lips engaged on [r_in, r_out] (a ≤ r_in < r_out ≤ R) and the chisel in or out.
DrillingForces drillingForcesEngaged(const DrillingModel& model, DrillingData& data, double feed,
                                     double r_in, double r_out, bool chisel_engaged);

/// Engagement at tip depth z below the entry surface (§2.1); `thickness` ≤ 0 means a blind hole.
struct Engagement {
  double r_in{0}, r_out{0};
  bool chisel{true};
  bool cutting{true};
};
Engagement engagementAtDepth(const DrillGeometry& g, double depth, double thickness);

/// Forces at tip depth z (entry ramp, steady, breakthrough).
DrillingForces drillingForcesAtDepth(const DrillingModel& model, DrillingData& data, double feed,
                                     double depth, double thickness);

struct DepthSample {
  double depth{0};  ///< tip depth below the entry surface [m]
  DrillingForces forces;
};
/// Range limits (a depth of 1e300 mm or a step of 1e-12 mm overflowed the sample
/// count): hole depth at most 2 m, a depth profile or an axial coupling at most 1e6 rows.
inline constexpr double kMaxHoleDepth = 2.0;              ///< [m]
inline constexpr double kMaxDepthSamples = 1.0e6;         ///< rows of a depth profile
inline constexpr double kMaxCouplingRevolutions = 1.0e6;  ///< rows of an axial coupling

/// "" when a depth profile of `hole_depth` every `step` is within range, else what is wrong
/// (numbers in mm, bounded %g).
std::string depthProfileProblem(const DrillingModel& model, double hole_depth, bool through,
                                double step);
/// "" when an axial coupling of `hole_depth` at `feed` per revolution is within range.
std::string axialCouplingProblem(const DrillingModel& model, double feed, double hole_depth,
                                 bool through);

/// Samples from z = 0 to the hole depth (blind) or through the breakthrough (thickness > 0:
/// until the corner has left the plate), every `step` metres. Throws InputError when
/// depthProfileProblem() is not empty.
std::vector<DepthSample> drillingDepthProfile(const DrillingModel& model, DrillingData& data,
                                              double feed, double hole_depth, bool through,
                                              double step);

/// Feed absorbed by the robot's axial compliance during the cut (docs/process.md §2.1, the drilling
/// analogue of the milling correction). Quasi-static, one step per spindle revolution k:
///   f_k = f − (δ_k − δ_{k−1}),  z_k = z_{k−1} + f_k,  δ_k = c_z · Fz(z_k, f_k)
/// (δ = axial deflection of the TCP against the feed [m], c_z = axial compliance [m/N]). Each
/// revolution is a scalar root of g(δ) = δ − c_z Fz(f − (δ − δ_{k−1})), monotonic in δ, bracketed
/// on [δ_{k−1}, δ_{k−1} + f] and solved by the Illinois false-position method to `tolerance`, so it
/// converges also when the loop gain c_z ∂Fz/∂f exceeds 1 (where a fixed-point iteration would
/// not).
struct AxialCouplingSample {
  int revolution{0};
  double depth{0};       ///< z_k, tip depth reached [m]
  double feed{0};        ///< f_k, actual feed of this revolution [m]
  double deflection{0};  ///< δ_k [m]
  bool converged{false};
  int iterations{0};
  double residual{0};  ///< |g(δ_k)| [m]
  DrillingForces forces;
};
/// Throws InputError when axialCouplingProblem() is not empty.
std::vector<AxialCouplingSample> drillingAxialCoupling(
    const DrillingModel& model, DrillingData& data, double feed, double hole_depth, bool through,
    double axial_compliance, double tolerance = 0.1e-6, int max_iterations = 100);

/// Single-test calibration (docs/process.md §2.3): all forces are linear in kst0 (torque) and ksa0
/// (thrust, including a chisel proportional to ksa0), so one measured (Fz, M) at one diameter
/// and feed fixes both in closed form: kst0' = kst0 · M_meas / M_model, ksa0' = ksa0 · Fz_meas /
/// Fz_model.
struct DrillingCalibration {
  DrillingCoefficients coeff;
  double thrust_model_before{0}, torque_model_before{0};  ///< prior predictions at the test point
  double thrust_model_after{0}, torque_model_after{0};    ///< after calibration (= measured)
};
DrillingCalibration calibrateDrilling(const DrillingModel& model, double feed,
                                      double thrust_measured, double torque_measured);

}  // namespace roprec
