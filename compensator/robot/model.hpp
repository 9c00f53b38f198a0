#pragma once
/// \file model.hpp
/// A serial 6R robot in **mixed natural coordinates** (García de Jalón & Bayo 1994; roprec
/// docs/model.md §1–§5): Cartesian points and unit vectors shared at the joints, plus the six
/// relative joint angles. Immutable `Model` built once from a ChainDescription (+ tool);
/// per-evaluation scratch in `Data`; algorithms are free functions `f(const Model&, Data&, ...)`
/// that allocate nothing.
///
/// ## Coordinates (generic serial construction, docs/model.md §1.3, §7.1)
/// Every moving body i (i = 0..5, the child link of joint i+1) is one point and an orthonormal
/// triad (u_i, v_i, w_i):
///   * p_i, u_i — a point on joint i's axis (the joint frame origin) and the axis; **shared** with
///     the parent body (for i = 0 they are ground constants);
///   * v_i — a unit vector of body i perpendicular to u_i (new), w_i = u_i × v_i (auxiliary, C7);
///   * p_{i+1}, u_{i+1} — the next joint's point and axis, fixed in body i (new, shared with i+1).
/// q = [v_0 w_0 p_1 u_1 | v_1 w_1 p_2 u_2 | … | v_4 w_4 p_5 u_5 | v_5 w_5 | θ_1 … θ_6],
/// n = 5·12 + 6 + 6 = **72** coordinates, z = θ (URDF joint angles, rad) the independent ones.
/// Because every body has an orthonormal triad, X̄ = [ū v̄ w̄] is orthonormal: no conditioning
/// problem for coplanar directions (small a3 on KUKA arms, pitfall §7.1) and a constant mass
/// matrix M (§4).
///
/// ## Constraints Φ(q) = 0 (m = 66; catalogue of docs/model.md §2)
/// Per body i, rows 11·i + …  (body 5: rows 55..59):
///   0   v·v − 1                       (C2)
///   1   v·u                           (C3, α = 90°)
///   2-4 w − u × v                     (C7)
///   5-7 p_{i+1} − p_i − (c₁u + c₂v + c₃w)   (C6, constant local coordinates c = X̄ᵀ p̄_{i+1})
///   8-10 u_{i+1} − (e₁u + e₂v + e₃w)        (C6 for a vector, e = X̄ᵀ ū_{i+1})
/// Angle rows 60 + i, with a_i = α₁u_{i-1} + α₂v_{i-1} + α₃w_{i-1} fixed in the parent (ground
/// constant for i = 0) and chosen so that θ⁰ = 0 (θ equals the URDF joint value):
///   dot form   (C8)  a·v − cos θ          cross form (C9)  u·(a × v) − sin θ
/// The form is chosen once per configuration: dot when |sin θ| > √2/2 (docs/model.md §2.4).
///
/// ## Leading matrix A = [Φ_q; B] (72×72) and its structured solve
/// A is block lower-bidiagonal by bodies: body i's rows involve only body i's coordinates, its
/// angle and the parent's shared elements. Solving A x = r needs one 3×3 solve per body (for the
/// increment of v_i: rows v·v, v·u and the angle row); the others follow explicitly. Aᵀ y = b is
/// the exact adjoint (reverse sweep). A is never formed or inverted in the hot path; a dense
/// assembly exists for tests (`assemblePhiq`).
///
/// ## Kinematic problems (§3)
///   position:      Newton–Raphson A(q⁽ᵏ⁾) Δq = [−Φ(q⁽ᵏ⁾); 0]   (θ fixed)
///   velocity:      q̇ = R ż,  R = A⁻¹[0; I₆]        (72×6)
///   acceleration:  q̈ = R z̈ + Sc,  Sc = A⁻¹[c; 0],  c = −Φ̇_q q̇
///
/// Frames (Drake monogram): W = robot base frame (the chain's base link); L_i = URDF child link
/// of joint i+1; `p_W_tcp`, `R_W_tcp` the TCP (tip link × tool). Units SI.

#include <array>

#include "compensator/robot/chain.hpp"

namespace roprec::nc {

constexpr int kNz = 6;           ///< independent coordinates (joint angles)
constexpr int kNq = 72;          ///< natural + relative coordinates
constexpr int kNc = 66;          ///< constraints
constexpr int kAngleRow = 60;    ///< first angle-constraint row
constexpr int kAngleCoord = 66;  ///< first angle coordinate

using VecQ = Eigen::Matrix<double, kNq, 1>;
using VecC = Eigen::Matrix<double, kNc, 1>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using MatR = Eigen::Matrix<double, kNq, kNz>;

/// Index of v_i, w_i, p_{i+1}, u_{i+1} in q (the last two only for i < 5).
constexpr int idxV(int i) { return 12 * i; }
constexpr int idxW(int i) { return 12 * i + 3; }
constexpr int idxPnext(int i) { return 12 * i + 6; }
constexpr int idxUnext(int i) { return 12 * i + 9; }
constexpr int idxTheta(int i) { return kAngleCoord + i; }
/// First constraint row of body i.
constexpr int rowBody(int i) { return 11 * i; }

/// Constant description of one moving body (the child link L_i of joint i+1).
struct Body {
  Vec3 ubar{Vec3::UnitZ()};     ///< joint axis in L_i
  Vec3 vbar{Vec3::UnitX()};     ///< chosen unit vector ⊥ ubar, in L_i
  Vec3 wbar{Vec3::UnitY()};     ///< ubar × vbar
  Mat3 Xbar{Mat3::Identity()};  ///< [ubar vbar wbar] (orthonormal)
  Vec3 c_next{Vec3::Zero()};    ///< next joint point: p_{i+1} = p_i + X c_next (i < 5)
  Vec3 e_next{Vec3::Zero()};    ///< next joint axis: u_{i+1} = X e_next (i < 5)
  Vec3 alpha{Vec3::Zero()};     ///< a_i = X_{i-1} alpha (i > 0): parent-fixed angle reference
  Eigen::Matrix4d K{Eigen::Matrix4d::Zero()};  ///< M_B = K ⊗ I₃ over [p_i; u_i; v_i; w_i] (§4)
  double mass{0.0};            ///< kg (link + rigidly attached links; body 5 + tool)
  Vec3 com{Vec3::Zero()};      ///< m, in L_i
  Mat3 inertia{Mat3::Zero()};  ///< kg m², about com, L_i axes
  double lower{0.0};           ///< joint limits, rad
  double upper{0.0};
};

struct Model {
  std::array<Body, 6> bodies;
  Vec3 p0{Vec3::Zero()};               ///< ground: joint 1 point (base frame)
  Vec3 u0{Vec3::UnitZ()};              ///< ground: joint 1 axis
  Vec3 a0{Vec3::UnitX()};              ///< ground: joint 1 angle reference (⊥ u0)
  std::array<Pose, 6> origin;          ///< T_{L_{i-1}, J_i} from the chain (closed-form warm start)
  std::array<Vec3, 6> axis;            ///< joint axes in the joint frames
  Pose T_L6_flange{Pose::Identity()};  ///< tip link (flange) in L_5
  Pose T_L6_tcp{Pose::Identity()};     ///< TCP (flange × tool) in L_5
  Vec3 c_tcp{Vec3::Zero()};            ///< p_tcp = p_5 + X_5 c_tcp
  Mat3 Rbar_tcp{Mat3::Identity()};     ///< R_W_tcp = X_5 Rbar_tcp  (= X̄ᵀ R_L6_tcp)
  Vec3 gravity{0.0, 0.0, -9.80665};    ///< m/s², base frame (zero: gravity not modelled)
  /// Axis-2 balancer (counterbalance.hpp): its torque joins the gravity loads (inverse_dynamics).
  Counterbalance counterbalance;
  double tol_phi{1e-12};  ///< Newton: ‖Φ‖∞ tolerance (m, m²)
  int max_iterations{25};
};

/// Tool (TCP and rigid mass) attached to the flange.
struct ToolAttachment {
  Pose T_flange_tcp{Pose::Identity()};
  double mass{0.0};            ///< kg
  Vec3 com{Vec3::Zero()};      ///< m, flange frame
  Mat3 inertia{Mat3::Zero()};  ///< kg m², about com, flange axes
};

/// Builds the model. Links without inertial data get zero mass (kinematics unaffected). The
/// chain's counterbalance is copied; a chain with gravity_modelled false gets gravity = 0.
Model buildModel(const ChainDescription& chain, const ToolAttachment& tool = {});

/// Per-evaluation scratch, sized once (no allocation afterwards).
struct Data {
  explicit Data(const Model& model);
  Vec6 z{Vec6::Zero()};  ///< joint angles the state belongs to (rad)
  VecQ q{VecQ::Zero()};
  VecQ qd{VecQ::Zero()};
  VecQ qdd{VecQ::Zero()};
  VecC Phi{VecC::Zero()};
  std::array<bool, 6> cross_form{};  ///< angle-row form per joint (chosen per configuration)
  /// Per-body quantities at the factorised configuration: elements, angle reference, the
  /// inverse of the 3×3 pivot block G = [2vᵀ; uᵀ; ∂Φ_angle/∂v] and the angle row's partials.
  struct BodyCache {
    Vec3 u{Vec3::Zero()};
    Vec3 v{Vec3::Zero()};
    Vec3 w{Vec3::Zero()};
    Vec3 a{Vec3::Zero()};
    Vec3 g_du{Vec3::Zero()};  ///< ∂Φ_angle/∂u
    Vec3 g_da{Vec3::Zero()};  ///< ∂Φ_angle/∂a
    double g_th{0.0};         ///< ∂Φ_angle/∂θ
    Mat3 Ginv{Mat3::Identity()};
  };
  std::array<BodyCache, 6> body{};
  bool factorized{false};  ///< body[] matches q
  MatR R{MatR::Zero()};
  VecQ Sc{VecQ::Zero()};
  VecC c{VecC::Zero()};  ///< −Φ̇_q q̇
  VecQ scratch{VecQ::Zero()};
  VecQ scratch2{VecQ::Zero()};
  Eigen::Matrix<double, kNq, 1> rhs{Eigen::Matrix<double, kNq, 1>::Zero()};
  Vec6 tau{Vec6::Zero()};     ///< joint torques (N m), inverse dynamics
  VecC lambda{VecC::Zero()};  ///< constraint multipliers (joint reactions)
  Pose T_W_tcp{Pose::Identity()};
  Pose T_W_flange{Pose::Identity()};
  Mat6 J_tcp{Mat6::Zero()};  ///< [v; ω] = J_tcp ż (base frame, at the TCP)
  /// Link frames of the serial recursion (fast_equilibrium.hpp) at `theta`, base frame W:
  /// joint point p_W_Ji (= origin of L_i), unit axis u_i, R_W_Li, and the TCP.
  struct ChainFrames {
    Vec6 theta{Vec6::Zero()};
    Vec6 sin_theta{Vec6::Zero()};
    std::array<Vec3, 6> p{};
    std::array<Vec3, 6> u{};
    std::array<Mat3, 6> R{};
    Vec3 p_tcp{Vec3::Zero()};
    Mat3 R_tcp{Mat3::Identity()};
  };
  ChainFrames frames;
};

/// Result of the Newton–Raphson position problem (non-convergence is a value).
struct PositionResult {
  bool converged{false};
  int iterations{0};
  double residual{0.0};  ///< ‖Φ‖∞ at exit
};

enum class Guess {
  kClosedForm,  ///< forward recursion with Rodrigues rotations, then Newton polish
  kWarmStart,   ///< Newton from the q already in data (previous configuration)
};

/// Solves Φ(q) = 0 for the dependent coordinates with θ = z fixed (Newton–Raphson; the angle-row
/// forms are chosen once from z). The factorisation at the solution is made lazily by the
/// velocity/acceleration/dynamics functions (or explicitly with `factorize`).
PositionResult solvePosition(const Model& model, Data& data, const Vec6& z,
                             Guess guess = Guess::kClosedForm);

/// Φ(q) into data.Phi (uses data.cross_form).
void evaluatePhi(const Model& model, Data& data, const VecQ& q);
/// Chooses the angle-row forms from the angles in data.q and factorises the 3×3 blocks there.
void factorize(const Model& model, Data& data);

/// x = A⁻¹ r (r: 66 constraint rows then 6 B rows). x and r may not alias. Requires
/// `factorize` at data.q (velocityTransform/velocities/accelerationTerm do it when needed).
void solveA(const Model& model, const Data& data, const VecQ& r, VecQ& x);
/// y = A⁻ᵀ b (adjoint sweep). y and b may not alias.
void solveAT(const Model& model, const Data& data, const VecQ& b, VecQ& y);

/// R = A⁻¹[0; I] into data.R (72×6): ∂q/∂z.
const MatR& velocityTransform(const Model& model, Data& data);
/// q̇ = R ż into data.qd.
const VecQ& velocities(const Model& model, Data& data, const Vec6& zd);
/// c = −Φ̇_q q̇ (from data.qd, θ̇ = zd) and Sc = A⁻¹[c; 0] into data.c, data.Sc.
const VecQ& accelerationTerm(const Model& model, Data& data, const Vec6& zd);

/// TCP and flange poses from q (linear in q): data.T_W_tcp, data.T_W_flange.
void framePoses(const Model& model, Data& data);
/// TCP Jacobian [v; ω] (base frame, reference point TCP) from R: data.J_tcp. Calls
/// velocityTransform.
const Mat6& tcpJacobian(const Model& model, Data& data);

/// Forward kinematics convenience: position problem (closed-form guess) + frame poses.
PositionResult forwardKinematics(const Model& model, Data& data, const Vec6& z);

/// Dense Φ_q (66×72) for tests and diagnostics (allocation-free: caller's matrix).
void assemblePhiq(const Model& model, const Data& data, Eigen::Ref<Eigen::MatrixXd> Phi_q);

}  // namespace roprec::nc
