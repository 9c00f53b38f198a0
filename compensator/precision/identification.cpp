#include "compensator/precision/identification.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "compensator/precision/uncertainty.hpp"
#include "compensator/support/error.hpp"

namespace roprec {

const char* registrationName(Registration r) {
  switch (r) {
    case Registration::kNone:
      return "none";
    case Registration::kTranslation:
      return "translation";
    case Registration::kRigid:
      return "rigid";
  }
  return "?";
}

std::optional<Registration> registrationFromName(const std::string& name) {
  for (const Registration r :
       {Registration::kNone, Registration::kTranslation, Registration::kRigid}) {
    if (name == registrationName(r)) return r;
  }
  return std::nullopt;
}

const char* identifySetName(IdentifySet s) {
  switch (s) {
    case IdentifySet::kAll:
      return "all";
    case IdentifySet::kStiffness:
      return "stiffness";
    case IdentifySet::kGeometry:
      return "geometry";
    case IdentifySet::kNone:
      return "none";
  }
  return "?";
}

std::optional<IdentifySet> identifySetFromName(const std::string& name) {
  for (const IdentifySet s :
       {IdentifySet::kAll, IdentifySet::kStiffness, IdentifySet::kGeometry, IdentifySet::kNone}) {
    if (name == identifySetName(s)) return s;
  }
  return std::nullopt;
}

Vec6 compliancePriorSigma(const RobotCard& card, double estimate_rel, double known_rel) {
  Vec6 s;
  for (int j = 0; j < 6; ++j)
    s[j] = card.joints[static_cast<size_t>(j)].estimated() ? estimate_rel : known_rel;
  return s;
}

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

Mat3 rotationOf(const Vec3& w) {
  const double a = w.norm();
  return a > 0 ? Mat3(Eigen::AngleAxisd(a, w / a)) : Mat3::Identity();
}

// ---------------------------------------------------------------- parameters

/// Where each parameter group sits in x: c (0..5), then the tool (4), then the geometry (6 per
/// joint origin, 6 for the tip: δx δy δz δroll δpitch δyaw), then the registration.
struct Layout {
  int tool{-1};  ///< Δm, Δcom x/y/z
  int geo{-1};   ///< joint 1..6 origins, tip
  int reg{-1};   ///< t x/y/z [, ω x/y/z]
  int n_reg{0};
  int n{6};
};

constexpr int kGeometryParameters = 42;

Layout layoutOf(bool tool, bool geometry, Registration reg) {
  Layout l;
  if (tool) {
    l.tool = l.n;
    l.n += 4;
  }
  if (geometry) {
    l.geo = l.n;
    l.n += kGeometryParameters;
  }
  l.n_reg = reg == Registration::kNone ? 0 : reg == Registration::kTranslation ? 3 : 6;
  if (l.n_reg > 0) {
    l.reg = l.n;
    l.n += l.n_reg;
  }
  return l;
}

/// Is x_k a robot parameter (changes the prediction) rather than a registration one?
bool robotParameter(const Layout& l, int k) { return l.reg < 0 || k < l.reg; }

bool geometryParameter(const Layout& l, int k) {
  return l.geo >= 0 && k >= l.geo && k < l.geo + kGeometryParameters;
}

/// The FrameError that x's geometry block `e` (0..5 joints, 6 tip) describes.
FrameError frameErrorOf(const Layout& l, const VectorXd& x, int e) {
  FrameError f;
  f.dxyz = x.segment<3>(l.geo + 6 * e);
  f.drpy = x.segment<3>(l.geo + 6 * e + 3);
  return f;
}

FrameError& frameOf(GeometryCalibration& g, int e) {
  return e < 6 ? g.joints[static_cast<size_t>(e)] : g.tool;
}
const FrameError& frameOf(const GeometryCalibration& g, int e) {
  return e < 6 ? g.joints[static_cast<size_t>(e)] : g.tool;
}

/// Names, units, prior values (internal units: c relative) and σ, FD steps.
struct ParameterSpec {
  std::vector<std::string> name, unit;
  VectorXd x0, s0, step;
  VectorXd scale;  ///< internal → reported units (c_j: c⁰_eff,j; others 1)
};

void addParameter(ParameterSpec& p, int k, const std::string& name, const std::string& unit,
                  double x0, double s0, double step, double scale) {
  p.name[static_cast<size_t>(k)] = name;
  p.unit[static_cast<size_t>(k)] = unit;
  p.x0[k] = x0;
  p.s0[k] = s0;
  p.step[k] = step;
  p.scale[k] = scale;
}

/// The geometry parameters: prior = the card's calibration, σ = its stated σ or o's class values.
void addGeometry(ParameterSpec& p, const Layout& l, const GeometryCalibration& g0,
                 const IdentificationOptions& o) {
  const char* comp[] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int e = 0; e < 7; ++e) {
    const FrameError& f = frameOf(g0, e);
    const std::string prefix = e < 6 ? "j" + std::to_string(e + 1) + "_" : std::string("tip_");
    for (int a = 0; a < 6; ++a) {
      const bool rot = a >= 3;
      const double stated = rot ? f.sigma_rpy[a - 3] : f.sigma_xyz[a];
      const double s0 = stated > 0 ? stated : rot ? o.geometry_rpy_prior : o.geometry_xyz_prior;
      addParameter(p, l.geo + 6 * e + a, prefix + comp[a], rot ? "rad" : "m",
                   rot ? f.drpy[a - 3] : f.dxyz[a], s0,
                   rot ? o.geometry_rpy_step : o.geometry_xyz_step, 1.0);
    }
  }
}

ParameterSpec parameterSpec(const Layout& l, const Vec6& c0, const IdentificationOptions& o,
                            const GeometryCalibration& g0) {
  ParameterSpec p;
  p.name.resize(static_cast<size_t>(l.n));
  p.unit.resize(static_cast<size_t>(l.n));
  p.x0 = p.s0 = p.step = p.scale = VectorXd::Zero(l.n);
  for (int j = 0; j < 6; ++j) {
    std::string name(1, 'c');
    name += std::to_string(j + 1);
    addParameter(p, j, name, "rad/(N m)", 1.0, o.compliance_prior_rel[j], o.relative_step, c0[j]);
  }
  if (l.tool >= 0) {
    addParameter(p, l.tool, "tool_mass", "kg", 0.0, o.tool_mass_prior, o.mass_step, 1.0);
    const char* axes[] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      addParameter(p, l.tool + 1 + a, std::string("tool_com_") + axes[a], "m", 0.0,
                   o.tool_com_prior, o.com_step, 1.0);
    }
  }
  if (l.geo >= 0) addGeometry(p, l, g0, o);
  if (l.reg >= 0) {
    const char* names[] = {"reg_tx", "reg_ty", "reg_tz", "reg_rx", "reg_ry", "reg_rz"};
    for (int a = 0; a < l.n_reg; ++a) {
      const bool rot = a >= 3;
      addParameter(p, l.reg + a, names[a], rot ? "rad" : "m", 0.0,
                   rot ? o.rotation_prior : o.translation_prior,
                   rot ? o.rotation_step : o.translation_step, 1.0);
    }
  }
  return p;
}

// ---------------------------------------------------------------- the problem

/// Everything an evaluation needs, set up once.
struct Problem {
  const PredictionModel& m;
  const std::vector<IdentificationHole>& holes;
  Layout layout;
  ParameterSpec spec;
  Vec6 c0{Vec6::Zero()};  ///< prior effective compliance, rad/(N m)
  std::optional<nc::ToolAttachment> tool;
  Pose T_W_wobj{Pose::Identity()};
  std::vector<nc::Loads> loads;   ///< per hole
  std::vector<Vec3> d_mach_tool;  ///< δmach in the tool frame, per hole
  nc::Data data;
  IdentifySet identify{IdentifySet::kAll};
  std::vector<Eigen::Index> row;  ///< first residual row of each observation; back() = total
  /// Per observation with its own tool, its model (null: the problem's). A pointer, not an
  /// optional: a 4 kB model per observation would be written (and kept resident) for the
  /// 64,000 candidates of a test plan, which have none.
  std::vector<std::unique_ptr<const nc::Model>> obs_model;
  // geometry: p̂ = p̂_model + TCP(calibratedChain(nominal, G(x)), θ) − TCP(m's chain, θ)
  GeometryCalibration g0;  ///< the card's (the prior; its base is kept)
  Pose T_flange_tcp{Pose::Identity()};
  /// The equilibrium depends on the non-geometry parameters only: their last value, θ and p̂
  /// without the geometry term, and the TCP of m's own chain at θ.
  VectorXd cache_key;
  std::vector<Vec6> cache_theta;
  std::vector<Pose> cache_p, cache_tcp_ref;
  /// Per hole: the torques of the controller's command offset at θ_cmd (offsetTorque), which do
  /// not change with x; the offset is τ ⊘ c_eff(x).
  std::vector<Vec6> offset_torque;
};

/// The non-geometry part of x (the key of the equilibrium cache).
VectorXd equilibriumKey(const Layout& l, const VectorXd& x) {
  if (l.geo < 0) return x;
  VectorXd k(x.size() - kGeometryParameters);
  k << x.head(l.geo), x.tail(x.size() - l.geo - kGeometryParameters);
  return k;
}

/// May x_k move in this identification (IdentificationOptions::identify)?
bool freeParameter(const Problem& P, int k) {
  if (!robotParameter(P.layout, k)) return true;
  if (P.identify == IdentifySet::kNone) return false;
  if (k < 6) return P.identify == IdentifySet::kAll || P.identify == IdentifySet::kStiffness;
  if (geometryParameter(P.layout, k))
    return P.identify == IdentifySet::kAll || P.identify == IdentifySet::kGeometry;
  return true;  // tool mass/COM: asked for explicitly
}

std::vector<int> freeColumns(const Problem& P) {
  std::vector<int> c;
  for (int k = 0; k < P.layout.n; ++k) {
    if (freeParameter(P, k)) c.push_back(k);
  }
  return c;
}

Vec6 priorEffectiveCompliance(const PredictionModel& m) {
  return m.compliance.effective().cwiseInverse();
}

/// The process fields of an observation as a hole request (processFor).
HoleRequest processRequest(const IdentificationHole& h) {
  HoleRequest r;
  r.id = h.id;
  r.diameter = h.diameter;
  r.drill = h.drill;
  r.feed = h.feed;
  r.spindle_rpm = h.spindle_rpm;
  return r;
}

/// The torques the controller's command offset divides by K_eff at θ_cmd (controllerOffset =
/// τ ⊘ c.effective() for every controller reference): the offset for a unit effective
/// stiffness (k = 1, ideal servo: k_eff = 1 / (1 / 1 + 1 / ∞) = 1 exactly, so τ ⊘ 1 = τ).
Vec6 offsetTorque(Problem& P, const Vec6& theta_cmd) {
  nc::JointCompliance unit;
  unit.k = Vec6::Ones();
  unit.k_servo = Vec6::Constant(std::numeric_limits<double>::infinity());
  return controllerOffset(P.m, P.data, theta_cmd, unit);
}

void setUpHoles(Problem& P) {
  P.row.assign(1, 0);
  P.obs_model.clear();
  P.obs_model.resize(P.holes.size());
  P.offset_torque.clear();
  for (size_t i = 0; i < P.holes.size(); ++i) {
    const IdentificationHole& h = P.holes[i];
    if (h.tool) {
      if (P.layout.tool >= 0)
        throw InputError("", 0,
                         "observation '" + h.id +
                             "' has a payload: the tool cannot be identified together with "
                             "payload rows");
      auto model = std::make_unique<nc::Model>(nc::buildModel(P.m.robot.real_chain, *h.tool));
      model->gravity = P.m.model.gravity;
      model->tol_phi = P.m.model.tol_phi;
      model->max_iterations = P.m.model.max_iterations;
      P.obs_model[i] = std::move(model);
    }
    const ProcessAtDiameter* proc = h.point ? nullptr : processFor(P.m, processRequest(h));
    P.loads.push_back(h.loads ? *h.loads : processLoads(P.m, proc));
    P.d_mach_tool.push_back(proc ? Vec3(proc->mach.delta_tool.x(), proc->mach.delta_tool.y(), 0.0)
                                 : Vec3::Zero());
    P.row.push_back(P.row.back() + observationRows(h) + orientationRows(h));
    P.offset_torque.push_back(offsetTorque(P, h.theta_cmd));
  }
}

/// The problem of identifying `o`'s parameters of `m` from `holes` (set up, not evaluated).
Problem makeProblem(const PredictionModel& m, const std::vector<IdentificationHole>& holes,
                    const IdentificationOptions& o) {
  Problem P{m,
            holes,
            layoutOf(o.tool.has_value(), o.geometry, o.registration),
            {},
            priorEffectiveCompliance(m),
            o.tool,
            o.T_W_wobj,
            {},
            {},
            nc::Data(m.model),
            o.identify,
            {},
            {},
            cardGeometry(m),
            m.robot.real_chain.tip.inverse() * m.model.T_L6_tcp,
            {},
            {},
            {},
            {},
            {}};
  P.spec = parameterSpec(P.layout, P.c0, o, P.g0);
  setUpHoles(P);
  return P;
}

/// The model with the candidate tool (mass and centre of mass shifted by x).
nc::Model toolModel(const Problem& P, const VectorXd& x) {
  nc::ToolAttachment t = *P.tool;
  t.mass += x[P.layout.tool];
  t.com += x.segment<3>(P.layout.tool + 1);
  nc::Model model = nc::buildModel(P.m.robot.real_chain, t);
  model.gravity = P.m.model.gravity;
  model.tol_phi = P.m.model.tol_phi;
  model.max_iterations = P.m.model.max_iterations;
  return model;
}

/// The effective compliance of x as a JointCompliance (servo folded in: k = 1/c_eff, ideal servo).
nc::JointCompliance complianceOf(const Problem& P, const VectorXd& x) {
  nc::JointCompliance c;
  for (int j = 0; j < 6; ++j) c.k[j] = 1.0 / (x[j] * P.c0[j]);
  return c;
}

/// Geometry bounds inside the fit: a joint-origin or tip error beyond these is not a calibration
/// error (card check refuses it: 5 mm / 20 mrad), so a step that leaves the box is rejected (the
/// damping grows) rather than taken and reverted afterwards.
constexpr double kGeometryXyzBound = 5e-3;   // m
constexpr double kGeometryRpyBound = 20e-3;  // rad

/// The smallest effective compliance of joint j inside the fit, as a factor of its prior c0_j: the
/// servo's compliance plus kComplianceFloor of the prior joint compliance (a joint at most 1000 ×
/// stiffer than the card says). Below it the joint would be stiffer than its servo: not physical.
constexpr double kComplianceFloor = 1e-3;

double complianceLowerBound(const Problem& P, int j) {
  const double k_servo = P.m.compliance.k_servo[j];
  const double c_servo = k_servo < 1e299 ? 1.0 / k_servo : 0.0;
  const double c0 = P.c0[j];
  return (c_servo + kComplianceFloor * std::max(c0 - c_servo, 0.0)) / c0;
}

/// Projects a candidate onto the physical region: every compliance at least its lower bound (a
/// projected Levenberg–Marquardt step: the cost is evaluated at the projected point).
VectorXd projected(const Problem& P, VectorXd x) {
  for (int j = 0; j < 6; ++j) x[j] = std::max(x[j], complianceLowerBound(P, j));
  return x;
}

/// Compliances stay physical inside the fit (projected steps, projected()); the geometry stays
/// inside its bounds (a step leaving the box is rejected).
bool admissible(const Layout& l, const VectorXd& x) {
  if (!x.allFinite()) return false;
  for (int k = 0; l.geo >= 0 && k < kGeometryParameters; ++k) {
    const bool rot = k % 6 >= 3;
    if (std::abs(x[l.geo + k]) > (rot ? kGeometryRpyBound : kGeometryXyzBound)) return false;
  }
  return true;
}

/// The equilibria below read the TCP and θ only (P.data is their scratch): the frames suffice.
constexpr nc::DeflectionOptions kFramesOnly{.natural_state = false};

/// p̂_W of every hole at x without the geometry term (the real TCP's orientation with it), and
/// the real joint angles θ.
int predictEquilibrium(Problem& P, const VectorXd& x, std::vector<Pose>& p,
                       std::vector<Vec6>& theta) {
  const nc::JointCompliance c = complianceOf(P, x);
  std::optional<nc::Model> rebuilt;
  if (P.layout.tool >= 0) rebuilt = toolModel(P, x);
  const nc::Model& tool_model = rebuilt ? *rebuilt : P.m.model;
  p.resize(P.holes.size());
  theta.resize(P.holes.size());
  const Vec6 c_eff = c.effective();
  for (size_t i = 0; i < P.holes.size(); ++i) {
    const nc::Model& model = P.obs_model[i] ? *P.obs_model[i] : tool_model;
    const Vec6& th = P.holes[i].theta_cmd;
    // controllerOffset(P.m, P.data, th, c): the same torques over the same c_eff
    const Vec6 offset = P.m.controller.kind == nc::ControllerReference::Kind::kNone
                            ? Vec6::Zero()
                            : Vec6(P.offset_torque[i].cwiseQuotient(c_eff));
    const nc::Deflection d =
        nc::predictDeflection(model, P.data, c, th, P.loads[i], kFramesOnly, offset);
    if (!d.converged || !d.position_converged) return static_cast<int>(i);
    p[i] = d.T_real;
    p[i].translation() += d.T_nominal.linear() * P.d_mach_tool[i];
    theta[i] = d.theta;
  }
  return -1;
}

/// The geometry x describes: the card's base, x's joint origins and tip.
GeometryCalibration geometryOf(const Problem& P, const VectorXd& x) {
  GeometryCalibration g = P.g0;
  for (int e = 0; e < 7; ++e) {
    const FrameError f = frameErrorOf(P.layout, x, e);
    frameOf(g, e).dxyz = f.dxyz;
    frameOf(g, e).drpy = f.drpy;
  }
  return g;
}

/// p̂_W of every hole at x (and the real TCP's orientation). Returns the index of the first hole
/// whose equilibrium fails, or −1. Geometry enters as FK_G(θ) − FK_m(θ) at the equilibrium θ of
/// m's own geometry (the geometry errors change the torques by a relative 1e-3 at most, far below
/// the compliance's σ); the orientation as R_G(θ) R_m(θ)ᵀ R̂.
int predictRobot(Problem& P, const VectorXd& x, std::vector<Pose>& p) {
  if (P.layout.geo < 0) {
    std::vector<Vec6> theta;
    return predictEquilibrium(P, x, p, theta);
  }
  const VectorXd key = equilibriumKey(P.layout, x);
  if (P.cache_key.size() != key.size() || P.cache_key != key) {
    const int bad = predictEquilibrium(P, x, P.cache_p, P.cache_theta);
    if (bad >= 0) {
      P.cache_key.resize(0);
      return bad;
    }
    P.cache_key = key;
    P.cache_tcp_ref.resize(P.holes.size());
    for (size_t i = 0; i < P.holes.size(); ++i) {
      P.cache_tcp_ref[i] =
          chainForwardKinematics(P.m.robot.real_chain, P.cache_theta[i]) * P.T_flange_tcp;
    }
  }
  const ChainDescription real = calibratedChain(P.m.robot.chain, geometryOf(P, x));
  p.assign(P.holes.size(), Pose::Identity());
  for (size_t i = 0; i < P.holes.size(); ++i) {
    const Pose tcp = chainForwardKinematics(real, P.cache_theta[i]) * P.T_flange_tcp;
    p[i].translation() =
        P.cache_p[i].translation() + tcp.translation() - P.cache_tcp_ref[i].translation();
    p[i].linear() = tcp.linear() * P.cache_tcp_ref[i].linear().transpose() * P.cache_p[i].linear();
  }
  return -1;
}

/// The registration of x as a base-frame motion: m = T_W_wobj [R(ω), t] T_W_wobj⁻¹ p.
Pose registrationMotion(const Problem& P, const VectorXd& x) {
  if (P.layout.reg < 0) return Pose::Identity();
  const Vec3 t = x.segment<3>(P.layout.reg);
  const Vec3 w = P.layout.n_reg == 6 ? Vec3(x.segment<3>(P.layout.reg + 3)) : Vec3::Zero();
  Pose G = Pose::Identity();
  G.linear() = rotationOf(w);
  G.translation() = t;
  return P.T_W_wobj * G * P.T_W_wobj.inverse();
}

/// m̂_W: the robot position as the CMM sees it through the registration of x.
Vec3 registered(const Problem& P, const VectorXd& x, const Vec3& p_W) {
  if (P.layout.reg < 0) return p_W;
  const Vec3 t = x.segment<3>(P.layout.reg);
  const Vec3 w = P.layout.n_reg == 6 ? Vec3(x.segment<3>(P.layout.reg + 3)) : Vec3::Zero();
  return P.T_W_wobj * (rotationOf(w) * (P.T_W_wobj.inverse() * p_W) + t);
}

/// Unweighted residual of observation i: [e₁ e₂]ᵀ (p_measured − m̂) for a hole, all three axes
/// of T_W_hole for a point.
VectorXd inPlaneResidual(const Problem& P, const VectorXd& x, size_t i, const Pose& p_W) {
  const IdentificationHole& h = P.holes[i];
  const Vec3 d = h.p_W_measured - registered(P, x, p_W.translation());
  const Mat3 R = h.T_W_hole.linear();
  if (h.point) return R.transpose() * d;
  return Eigen::Vector2d(R.col(0).dot(d), R.col(1).dot(d));
}

/// Unweighted orientation residual of observation i (rad, T_W_hole's axes): the small rotation
/// from the predicted orientation, seen through the registration, to the measured one; zero
/// without a measured orientation.
Vec3 rotationResidual(const Problem& P, const VectorXd& x, size_t i, const Pose& p_W) {
  const IdentificationHole& h = P.holes[i];
  if (orientationRows(h) == 0) return Vec3::Zero();
  const Mat3 R_seen = registrationMotion(P, x).linear() * p_W.linear();
  const Eigen::AngleAxisd e(Mat3(*h.R_W_measured * R_seen.transpose()));
  return h.T_W_hole.linear().transpose() * (e.angle() * e.axis());
}

/// σ-weighted data residuals r (2 rows per hole, 3 per point, 3 more for a measured
/// orientation).
VectorXd dataResiduals(const Problem& P, const VectorXd& x, const std::vector<Pose>& p) {
  VectorXd r(P.row.back());
  for (size_t i = 0; i < P.holes.size(); ++i) {
    const IdentificationHole& h = P.holes[i];
    Eigen::Index n = 2;
    if (h.point) {
      const VectorXd e = inPlaneResidual(P, x, i, p[i]) / h.sigma;
      r.segment(P.row[i], e.size()) = e;
      n = e.size();
    } else {  // inPlaneResidual's two rows, written in place (no vector per hole)
      const Vec3 d = h.p_W_measured - registered(P, x, p[i].translation());
      const Mat3 R = h.T_W_hole.linear();
      r[P.row[i]] = R.col(0).dot(d) / h.sigma;
      r[P.row[i] + 1] = R.col(1).dot(d) / h.sigma;
    }
    if (orientationRows(h) > 0)
      r.segment<3>(P.row[i] + n) = rotationResidual(P, x, i, p[i]) / h.sigma_rotation;
  }
  return r;
}

double priorCost(const Problem& P, const VectorXd& x) {
  return (x - P.spec.x0).cwiseQuotient(P.spec.s0).squaredNorm();
}

/// Central-difference J_d = ∂r/∂x for the columns `cols`; registration columns reuse p at x.
/// Returns false when an equilibrium fails at a perturbed point.
bool dataJacobian(Problem& P, const VectorXd& x, const std::vector<Pose>& p_x,
                  const std::vector<int>& cols, MatrixXd& J) {
  J.resize(P.row.back(), static_cast<Eigen::Index>(cols.size()));
  std::vector<Pose> pp;
  std::vector<Pose> pm;
  for (size_t c = 0; c < cols.size(); ++c) {
    const int k = cols[c];
    const double h = P.spec.step[k];
    VectorXd xp = x;
    VectorXd xm = x;
    xp[k] += h;
    xm[k] -= h;
    if (robotParameter(P.layout, k)) {
      if (predictRobot(P, xp, pp) >= 0 || predictRobot(P, xm, pm) >= 0) return false;
      J.col(static_cast<Eigen::Index>(c)) =
          (dataResiduals(P, xp, pp) - dataResiduals(P, xm, pm)) / (2 * h);
    } else {
      J.col(static_cast<Eigen::Index>(c)) =
          (dataResiduals(P, xp, p_x) - dataResiduals(P, xm, p_x)) / (2 * h);
    }
  }
  return true;
}

/// J_wᵀJ_w restricted to `cols`: data part + the prior's diagonal.
MatrixXd normalMatrix(const Problem& P, const MatrixXd& J, const std::vector<int>& cols) {
  MatrixXd A = J.transpose() * J;
  for (size_t c = 0; c < cols.size(); ++c) {
    const double s = P.spec.s0[cols[c]];
    A(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(c)) += 1.0 / (s * s);
  }
  return A;
}

// ---------------------------------------------------------------- Levenberg–Marquardt

struct LmState {
  VectorXd x;
  std::vector<Pose> p;  ///< p̂ at x (and the real TCP's orientation)
  VectorXd r;           ///< weighted data residuals at x
  double cost{0};
};

struct LmOutcome {
  LmState state;
  bool converged{false};
  int iterations{0};
  std::string message;
};

/// Evaluates x; false when x is not admissible or an equilibrium fails.
bool evaluate(Problem& P, const VectorXd& x, LmState& s) {
  if (!admissible(P.layout, x)) return false;
  std::vector<Pose> p;
  if (predictRobot(P, x, p) >= 0) return false;
  s.x = x;
  s.p = std::move(p);
  s.r = dataResiduals(P, x, s.p);
  s.cost = s.r.squaredNorm() + priorCost(P, x);
  return true;
}

/// The gradient J_wᵀ r_w restricted to `cols`.
VectorXd gradient(const Problem& P, const MatrixXd& J, const LmState& s,
                  const std::vector<int>& cols) {
  VectorXd g = J.transpose() * s.r;
  for (size_t c = 0; c < cols.size(); ++c) {
    const int k = cols[c];
    g[static_cast<Eigen::Index>(c)] += (s.x[k] - P.spec.x0[k]) / (P.spec.s0[k] * P.spec.s0[k]);
  }
  return g;
}

/// The step on the free columns for damping λ, scattered into the full vector.
VectorXd dampedStep(const MatrixXd& A, const VectorXd& g, double lambda,
                    const std::vector<int>& cols, int n) {
  MatrixXd Al = A;
  Al.diagonal() += lambda * A.diagonal();
  const VectorXd d = -Al.ldlt().solve(g);
  VectorXd dx = VectorXd::Zero(n);
  for (size_t c = 0; c < cols.size(); ++c) dx[cols[c]] = d[static_cast<Eigen::Index>(c)];
  return dx;
}

double scaledSize(const Problem& P, const VectorXd& dx) {
  return dx.cwiseQuotient(P.spec.s0).cwiseAbs().maxCoeff();
}

/// Raises λ (×10) until a damped step does not increase F and takes it; false when none does
/// below λ = 1e12. On success λ is lowered (÷10) for the next iteration.
bool takeStep(Problem& P, const MatrixXd& A, const VectorXd& g, const std::vector<int>& cols,
              double& lambda, LmState& state) {
  for (; lambda < 1e12; lambda *= 10) {
    LmState trial;
    if (evaluate(P, projected(P, state.x + dampedStep(A, g, lambda, cols, P.layout.n)), trial) &&
        trial.cost <= state.cost) {
      state = std::move(trial);
      lambda = std::max(lambda / 10, 1e-12);
      return true;
    }
  }
  return false;
}

LmOutcome levenbergMarquardt(Problem& P, const LmState& start, const std::vector<int>& cols,
                             int max_iterations, double tol) {
  LmOutcome out;
  out.state = start;
  double lambda = 1e-3;
  for (out.iterations = 0; out.iterations < max_iterations; ++out.iterations) {
    MatrixXd J;
    if (!dataJacobian(P, out.state.x, out.state.p, cols, J)) {
      out.message = "the equilibrium failed while differentiating";
      return out;
    }
    const MatrixXd A = normalMatrix(P, J, cols);
    const VectorXd g = gradient(P, J, out.state, cols);
    // the step actually taken: a compliance on its bound does not move
    const VectorXd dx =
        projected(P, out.state.x + dampedStep(A, g, lambda, cols, P.layout.n)) - out.state.x;
    const double step = scaledSize(P, dx);
    if (step <= tol) {  // the step is below the tolerance: converged
      LmState trial;
      if (evaluate(P, out.state.x + dx, trial) && trial.cost <= out.state.cost)
        out.state = std::move(trial);
      out.converged = true;
      ++out.iterations;
      return out;
    }
    if (!takeStep(P, A, g, cols, lambda,
                  out.state)) {  // at the evaluation's rounding floor if tiny
      out.converged = step <= 100 * tol;
      if (!out.converged) out.message = "no step lowers the cost";
      return out;
    }
  }
  out.message = "no convergence in " + std::to_string(max_iterations) + " iterations";
  return out;
}

// ---------------------------------------------------------------- statistics of the estimate

/// Posterior covariance on `cols` (internal units): (J_wᵀ J_w)⁻¹.
MatrixXd posterior(const Problem& P, const MatrixXd& J, const std::vector<int>& cols) {
  const MatrixXd A = normalMatrix(P, J, cols);
  return A.ldlt().solve(MatrixXd::Identity(A.rows(), A.cols()));
}

/// Condition number of JᵀJ with the columns of J scaled to unit norm.
double scaledCondition(const MatrixXd& J) {
  MatrixXd Js = J;
  for (Eigen::Index c = 0; c < Js.cols(); ++c) {
    const double n = Js.col(c).norm();
    if (!(n > 0)) return std::numeric_limits<double>::infinity();
    Js.col(c) /= n;
  }
  const Eigen::SelfAdjointEigenSolver<MatrixXd> es(Js.transpose() * Js);
  const double lo = es.eigenvalues().minCoeff();
  const double hi = es.eigenvalues().maxCoeff();
  return lo > 0 ? hi / lo : std::numeric_limits<double>::infinity();
}

std::vector<int> allColumns(int n) {
  std::vector<int> c(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) c[static_cast<size_t>(k)] = k;
  return c;
}

double rmsNorm(const std::vector<VectorXd>& r) {
  double s = 0;
  for (const auto& v : r) s += v.squaredNorm();
  return r.empty() ? 0.0 : std::sqrt(s / static_cast<double>(r.size()));
}

std::vector<VectorXd> inPlaneResiduals(const Problem& P, const LmState& s) {
  std::vector<VectorXd> r;
  for (size_t i = 0; i < P.holes.size(); ++i) r.push_back(inPlaneResidual(P, s.x, i, s.p[i]));
  return r;
}

std::vector<Vec3> rotationResiduals(const Problem& P, const LmState& s) {
  std::vector<Vec3> r;
  for (size_t i = 0; i < P.holes.size(); ++i) r.push_back(rotationResidual(P, s.x, i, s.p[i]));
  return r;
}

// ---------------------------------------------------------------- set-up and results

void validateHoles(const std::vector<IdentificationHole>& holes) {
  if (holes.empty()) throw InputError("", 0, "no measured holes to identify from");
  for (const IdentificationHole& h : holes) {
    if (!(h.sigma > 0) || !std::isfinite(h.sigma)) {
      throw InputError("", 0, "hole '" + h.id + "': the measurement σ must be > 0");
    }
    if (orientationRows(h) > 0 && (!(h.sigma_rotation > 0) || !std::isfinite(h.sigma_rotation)))
      throw InputError("", 0, "pose '" + h.id + "': the orientation σ must be > 0");
  }
}

/// The state at the prior; throws InputError naming the hole whose equilibrium fails.
LmState priorState(Problem& P) {
  std::vector<Pose> p;
  const int bad = predictRobot(P, P.spec.x0, p);
  if (bad >= 0) {
    throw InputError("", 0,
                     "hole '" + P.holes[static_cast<size_t>(bad)].id +
                         "': the compliance equilibrium does not converge at the card's stiffness");
  }
  LmState s;  // evaluate(P, x0, s) without a second equilibrium pass (p is p̂ at x0)
  if (!admissible(P.layout, P.spec.x0)) return s;
  s.x = P.spec.x0;
  s.p = std::move(p);
  s.r = dataResiduals(P, s.x, s.p);
  s.cost = s.r.squaredNorm() + priorCost(P, s.x);
  return s;
}

/// One Levenberg–Marquardt run on the columns `cols` (the others stay where the start has them).
struct Pass {
  LmOutcome lm;
  std::vector<int> cols;
};

Pass estimate(Problem& P, const LmState& start, const std::vector<int>& cols,
              const IdentificationOptions& o) {
  Pass pass;
  pass.cols = cols;
  pass.lm = levenbergMarquardt(P, start, cols, o.max_iterations, o.step_tolerance);
  return pass;
}

/// (J_wᵀJ_w)⁻¹ at the end of a pass on its columns; the prior where the data cannot be evaluated.
MatrixXd passCovariance(Problem& P, const Pass& pass) {
  MatrixXd J;
  if (!pass.cols.empty() && dataJacobian(P, pass.lm.state.x, pass.lm.state.p, pass.cols, J)) {
    return posterior(P, J, pass.cols);
  }
  MatrixXd C = MatrixXd::Zero(static_cast<Eigen::Index>(pass.cols.size()),
                              static_cast<Eigen::Index>(pass.cols.size()));
  for (size_t c = 0; c < pass.cols.size(); ++c) {
    C(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(c)) =
        P.spec.s0[pass.cols[c]] * P.spec.s0[pass.cols[c]];
  }
  return C;
}

/// passCovariance scattered into all parameters; the ones the pass kept fixed get their prior
/// variance (ρ = 1: nothing learnt about them).
MatrixXd fullCovariance(Problem& P, const Pass& pass) {
  const MatrixXd Cp = passCovariance(P, pass);
  MatrixXd C = P.spec.s0.cwiseAbs2().asDiagonal();
  for (size_t a = 0; a < pass.cols.size(); ++a) {
    for (size_t b = 0; b < pass.cols.size(); ++b) {
      C(pass.cols[a], pass.cols[b]) =
          Cp(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
    }
  }
  return C;
}

/// Posterior covariance (internal units, all parameters) with the fixed parameters as "consider"
/// parameters: they keep their prior S_f, and their uncertainty is carried into the estimated
/// ones through the sensitivity of the estimate, G = A_aa⁻¹ J_aᵀ J_f:
///   P_aa = A_aa⁻¹ + G S_f Gᵀ,   P_af = −G S_f,   P_ff = S_f.
MatrixXd considerCovariance(Problem& P, const LmState& s, const std::vector<int>& seen) {
  const int n = P.layout.n;
  std::vector<int> fixed;
  for (int k = 0; k < n; ++k) {
    if (std::find(seen.begin(), seen.end(), k) == seen.end()) fixed.push_back(k);
  }
  MatrixXd C = MatrixXd::Zero(n, n);
  for (const int k : fixed) C(k, k) = P.spec.s0[k] * P.spec.s0[k];
  MatrixXd Ja;
  MatrixXd Jf;
  if (seen.empty() || !dataJacobian(P, s.x, s.p, seen, Ja) ||
      !dataJacobian(P, s.x, s.p, fixed, Jf)) {
    for (const int k : seen) C(k, k) = P.spec.s0[k] * P.spec.s0[k];
    return C;
  }
  const MatrixXd Aa_inv = posterior(P, Ja, seen);
  const MatrixXd G = Aa_inv * (Ja.transpose() * Jf);
  VectorXd Sf(static_cast<Eigen::Index>(fixed.size()));
  for (size_t f = 0; f < fixed.size(); ++f)
    Sf[static_cast<Eigen::Index>(f)] = P.spec.s0[fixed[f]] * P.spec.s0[fixed[f]];
  const MatrixXd Paa = Aa_inv + G * Sf.asDiagonal() * G.transpose();
  const MatrixXd Paf = -G * Sf.asDiagonal();
  for (size_t a = 0; a < seen.size(); ++a) {
    for (size_t b = 0; b < seen.size(); ++b) {
      C(seen[a], seen[b]) = Paa(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
    }
    for (size_t f = 0; f < fixed.size(); ++f) {
      C(seen[a], fixed[f]) = C(fixed[f], seen[a]) =
          Paf(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(f));
    }
  }
  return C;
}

void fillParameters(const Problem& P, const MatrixXd& first_cov, const Pass& final_pass,
                    const MatrixXd& C_internal, double ratio_limit, IdentificationResult& r) {
  const int n = P.layout.n;
  r.covariance = C_internal;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) r.covariance(i, j) *= P.spec.scale[i] * P.spec.scale[j];
  }
  for (int k = 0; k < n; ++k) {
    IdentifiedParameter q;
    q.name = P.spec.name[static_cast<size_t>(k)];
    q.unit = P.spec.unit[static_cast<size_t>(k)];
    q.prior = P.spec.x0[k] * P.spec.scale[k];
    q.prior_sigma = P.spec.s0[k] * P.spec.scale[k];
    q.ratio = std::sqrt(std::max(0.0, first_cov(k, k))) / P.spec.s0[k];
    q.identifiable = freeParameter(P, k) && q.ratio <= ratio_limit;
    q.value = (q.identifiable ? final_pass.lm.state.x[k] : P.spec.x0[k]) * P.spec.scale[k];
    q.sigma = std::sqrt(r.covariance(k, k));
    r.parameters.push_back(q);
  }
}

/// k_j from the identified effective compliance (the prior servo compliance removed).
void fillCompliance(const PredictionModel& m, IdentificationResult& r) {
  r.compliance = m.compliance;
  for (int j = 0; j < 6; ++j) {
    const IdentifiedParameter& q = r.parameters[static_cast<size_t>(j)];
    const double c_servo = m.compliance.k_servo[j] < 1e299 ? 1.0 / m.compliance.k_servo[j] : 0.0;
    const double c_joint = q.value - c_servo;
    // on the fit's lower bound (complianceLowerBound): the data want a joint stiffer than physical
    const bool at_bound = c_joint <= kComplianceFloor * (q.prior - c_servo) * (1 + 1e-6);
    r.joint_identified[static_cast<size_t>(j)] = q.identifiable && c_joint > 0 && !at_bound;
    if (q.identifiable && c_joint > 0 && at_bound) {
      r.message += (r.message.empty() ? "" : "; ") + std::string("joint ") + std::to_string(j + 1) +
                   ": the compliance stopped at its physical bound (1000 × the card's stiffness); "
                   "the card keeps its stiffness";
    }
    if (q.identifiable && !(c_joint > 0)) {
      r.message += (r.message.empty() ? "" : "; ") + std::string("joint ") + std::to_string(j + 1) +
                   ": the identified compliance is not above the servo's (not physical); the card "
                   "keeps its stiffness";
    }
    if (r.joint_identified[static_cast<size_t>(j)]) r.compliance.k[j] = 1.0 / c_joint;
    const double k = r.compliance.k[j];
    r.k_sigma[j] = q.sigma * k * k;
  }
}

void fillToolAndRegistration(const Problem& P, const IdentificationOptions& o,
                             IdentificationResult& r) {
  const Layout& l = P.layout;
  if (l.tool >= 0) {
    r.tool_mass = o.tool->mass + r.parameters[static_cast<size_t>(l.tool)].value;
    if (!(*r.tool_mass > 0)) {
      r.message += (r.message.empty() ? "" : "; ") +
                   std::string("the identified tool mass is not positive (not physical)");
    }
    const auto t = static_cast<size_t>(l.tool);
    r.tool_com = o.tool->com + Vec3(r.parameters[t + 1].value, r.parameters[t + 2].value,
                                    r.parameters[t + 3].value);
  }
  r.registration.kind = o.registration;
  for (int a = 0; a < l.n_reg; ++a) {
    const IdentifiedParameter& q =
        r.parameters[static_cast<size_t>(l.reg) + static_cast<size_t>(a)];
    (a < 3 ? r.registration.translation : r.registration.rotation)[a % 3] = q.value;
    (a < 3 ? r.registration.translation_sigma : r.registration.rotation_sigma)[a % 3] = q.sigma;
  }
}

/// The parameters whose posterior σ (all free) is at most ratio_limit × their prior σ.
std::vector<int> identifiableColumns(const MatrixXd& first_cov, const Problem& P,
                                     double ratio_limit) {
  std::vector<int> cols;
  for (int k = 0; k < P.layout.n; ++k) {
    if (freeParameter(P, k) &&
        std::sqrt(std::max(0.0, first_cov(k, k))) / P.spec.s0[k] <= ratio_limit)
      cols.push_back(k);
  }
  return cols;
}

}  // namespace

Vec3 RegistrationEstimate::unregister(const Pose& T_W_wobj, const Vec3& p_W_measured) const {
  const Vec3 p_o = T_W_wobj.inverse() * p_W_measured;
  return T_W_wobj * (rotationOf(rotation).transpose() * (p_o - translation));
}

namespace {

/// Pass 2: the parameters outside `seen` fixed at their prior, the others re-estimated from the
/// pass-1 estimate (or from the prior when that point cannot be evaluated).
Pass reestimate(Problem& P, const Pass& first, const LmState& prior, const std::vector<int>& seen,
                const IdentificationOptions& o) {
  VectorXd x = first.lm.state.x;
  for (int k = 0; k < P.layout.n; ++k) {
    if (std::find(seen.begin(), seen.end(), k) == seen.end()) x[k] = P.spec.x0[k];
  }
  LmState start;
  if (!evaluate(P, x, start)) start = prior;
  return estimate(P, start, seen, o);
}

/// The free columns without those that are exact linear combinations of others, from the data
/// Jacobian at the prior (dependentFree).
std::vector<int> dependentFree(const Problem& P, MatrixXd J, const std::vector<int>& cols,
                               double tol, std::vector<std::string>& dependencies);

std::vector<int> independentColumns(Problem& P, const LmState& prior, const std::vector<int>& cols,
                                    double tol, std::vector<std::string>& dependencies) {
  MatrixXd J;
  if (cols.empty() || !dataJacobian(P, prior.x, prior.p, cols, J)) return cols;
  return dependentFree(P, J, cols, tol, dependencies);
}

/// Which parameter group keeps its place when two are exactly dependent: the registration (a
/// property of the part, not of the robot) first, then the compliances, the tool, the geometry.
int priority(const Layout& l, int k) {
  if (!robotParameter(l, k)) return 0;
  if (k < 6) return 1;
  if (geometryParameter(l, k)) return 3;
  return 2;
}

/// A column whose prior σ moves the σ-weighted residuals by less than this (2-norm over all of
/// them) is not seen by the data at all.
constexpr double kUnseen = 1e-3;

/// The columns `cols` of J (data Jacobian on those columns) without the dependent ones: taken in
/// priority order, a column is kept when the part of it (prior-σ scaled) that the kept columns do
/// not reproduce exceeds `tol` × its norm (a QR factorisation grown column by column); a dropped
/// column is reported with the combination of kept columns that reproduces it.
std::vector<int> dependentFree(const Problem& P, MatrixXd J, const std::vector<int>& cols,
                               double tol, std::vector<std::string>& dependencies) {
  for (size_t c = 0; c < cols.size(); ++c)
    J.col(static_cast<Eigen::Index>(c)) *= P.spec.s0[cols[c]];
  std::vector<size_t> order(cols.size());
  for (size_t c = 0; c < cols.size(); ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return priority(P.layout, cols[a]) < priority(P.layout, cols[b]);
  });
  std::vector<size_t> kept;
  MatrixXd K(J.rows(), 0);
  for (const size_t c : order) {
    const VectorXd col = J.col(static_cast<Eigen::Index>(c));
    const double norm = col.norm();
    VectorXd coef;
    double rest = norm;
    if (K.cols() > 0) {
      coef = K.colPivHouseholderQr().solve(col);
      rest = (col - K * coef).norm();
    }
    if (norm > kUnseen && rest > tol * norm) {
      kept.push_back(c);
      K.conservativeResize(Eigen::NoChange, K.cols() + 1);
      K.col(K.cols() - 1) = col;
      continue;
    }
    std::vector<std::pair<double, int>> terms;
    for (Eigen::Index a = 0; a < coef.size(); ++a)
      terms.emplace_back(coef[a], cols[kept[static_cast<size_t>(a)]]);
    std::stable_sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) {
      return std::abs(a.first) > std::abs(b.first);
    });
    std::string text = P.spec.name[static_cast<size_t>(cols[c])] + " ≡";
    size_t shown = 0;
    for (const auto& [v, k] : terms) {
      if (shown == 3 || std::abs(v) < 1e-3) break;
      text +=
          (shown++ ? " + " : " ") + numberText(v, 3) + " × " + P.spec.name[static_cast<size_t>(k)];
    }
    if (shown == 0 || norm <= kUnseen)
      text = P.spec.name[static_cast<size_t>(cols[c])] + " ≡ 0 (the data do not see it)";
    dependencies.push_back(text);
  }
  std::vector<int> out;
  for (const size_t c : kept) out.push_back(cols[c]);
  std::sort(out.begin(), out.end());
  return out;
}

/// The dependent parameters of the data Jacobian J (all columns), named.
void dependentNames(const Problem& P, const MatrixXd& J, double tol,
                    std::vector<std::string>& dependencies) {
  (void)dependentFree(P, J, allColumns(P.layout.n), tol, dependencies);
}

/// The posterior covariance of the geometry and the part's registration together (internal =
/// reported units for both), the registration restated as the base error it is to every hole:
/// m̂ = T_W_wobj (R(ω) T_W_wobj⁻¹ p + t) moves p by δm = R δt + (R δω) × (p − o) (R, o the
/// workobject's axes and origin), i.e. by the base translation δt_B = R δt + o × (R δω) and
/// rotation δω_B = R δω about the base origin: C = T Σ Tᵀ with T that linear map.
void calibrationCovariance(const Problem& P, const MatrixXd& cov, GeometryCalibration& g) {
  const Layout& l = P.layout;
  const int n_base = l.n_reg;  // 0, 3 (translation) or 6 (rigid)
  const int n = n_base + kGeometryParameters;
  MatrixXd T = MatrixXd::Zero(n, l.n);
  const Mat3& R = P.T_W_wobj.linear();
  const Vec3 o = P.T_W_wobj.translation();
  Mat3 ox;
  ox << 0, -o.z(), o.y(), o.z(), 0, -o.x(), -o.y(), o.x(), 0;
  if (n_base > 0) T.block(0, l.reg, 3, 3) = R;
  if (n_base == 6) {
    T.block(0, l.reg + 3, 3, 3) = ox * R;
    T.block(3, l.reg + 3, 3, 3) = R;
  }
  for (int k = 0; k < kGeometryParameters; ++k) T(n_base + k, l.geo + k) = 1.0;
  g.covariance = T * cov * T.transpose();
  const char* base[] = {"base_x", "base_y", "base_z", "base_rx", "base_ry", "base_rz"};
  for (int a = 0; a < n_base; ++a) g.covariance_parameters.emplace_back(base[a]);
  for (int k = 0; k < kGeometryParameters; ++k)
    g.covariance_parameters.push_back(P.spec.name[static_cast<size_t>(l.geo + k)]);
}

/// The identified geometry with σ from the posterior covariance.
GeometryCalibration identifiedGeometry(const Problem& P, const IdentificationResult& r) {
  GeometryCalibration g = P.g0;
  for (int e = 0; e < 7; ++e) {
    FrameError& f = frameOf(g, e);
    for (int a = 0; a < 6; ++a) {
      const auto k = static_cast<size_t>(P.layout.geo + 6 * e + a);
      (a < 3 ? f.dxyz : f.drpy)[a % 3] = r.parameters[k].value;
      (a < 3 ? f.sigma_xyz : f.sigma_rpy)[a % 3] = r.parameters[k].sigma;
    }
  }
  g.covariance_parameters.clear();
  calibrationCovariance(P, r.covariance, g);
  g.measurements = r.holes;
  return g;
}

/// The condition number of the pass's data Jacobian at its estimate; J is left in `J` (empty
/// when it cannot be evaluated).
double conditionOf(Problem& P, const Pass& pass, MatrixXd& J) {
  if (pass.cols.empty() || !dataJacobian(P, pass.lm.state.x, pass.lm.state.p, pass.cols, J)) {
    J.resize(0, 0);
    return std::numeric_limits<double>::infinity();
  }
  return scaledCondition(J);
}

}  // namespace

IdentificationResult identifyStiffness(const PredictionModel& m,
                                       const std::vector<IdentificationHole>& holes,
                                       const IdentificationOptions& o) {
  validateHoles(holes);
  Problem P = makeProblem(m, holes, o);
  const LmState prior = priorState(P);

  // exact dependencies out first (geometry only: without it the parameter set has none the
  // priors do not already settle)
  std::vector<std::string> dependencies;
  const std::vector<int> free =
      P.layout.geo >= 0
          ? independentColumns(P, prior, freeColumns(P), o.dependency_tolerance, dependencies)
          : freeColumns(P);
  // pass 1: every free parameter estimated; its posterior says what the data can see
  const Pass first = estimate(P, prior, free, o);
  const MatrixXd first_cov = fullCovariance(P, first);
  const std::vector<int> seen = identifiableColumns(first_cov, P, o.identifiable_ratio);
  // pass 2: what the data cannot see keeps its prior
  const bool refit = seen != first.cols;
  const Pass final_pass = refit ? reestimate(P, first, prior, seen, o) : first;

  IdentificationResult r;
  r.holes = static_cast<int>(holes.size());
  r.converged = first.lm.converged && final_pass.lm.converged;
  r.iterations = first.lm.iterations + (refit ? final_pass.lm.iterations : 0);
  r.message = final_pass.lm.message.empty() ? first.lm.message : final_pass.lm.message;
  r.condition_number = conditionOf(P, final_pass, r.jacobian);
  fillParameters(P, first_cov, final_pass, considerCovariance(P, final_pass.lm.state, seen),
                 o.identifiable_ratio, r);
  fillCompliance(m, r);
  fillToolAndRegistration(P, o, r);
  if (P.layout.geo >= 0) r.geometry = identifiedGeometry(P, r);
  r.dependencies = std::move(dependencies);
  r.residuals = inPlaneResiduals(P, final_pass.lm.state);
  r.rotation_residuals = rotationResiduals(P, final_pass.lm.state);
  r.rms_prior = rmsNorm(inPlaneResiduals(P, prior));
  r.rms_final = rmsNorm(r.residuals);
  r.chi2 = final_pass.lm.state.r.squaredNorm();
  r.equations = static_cast<int>(P.row.back());
  r.dof = r.equations - static_cast<int>(seen.size());
  return r;
}

namespace {

/// The state of `holes` at the parameters of `r` (residualsAt).
LmState stateAt(Problem& P, const IdentificationResult& r) {
  if (static_cast<int>(r.parameters.size()) != P.layout.n)
    throw InputError("", 0, "the identification does not match the validation's parameters");
  VectorXd x(P.layout.n);
  for (int k = 0; k < P.layout.n; ++k)
    x[k] = r.parameters[static_cast<size_t>(k)].value / P.spec.scale[k];
  std::vector<Pose> p;
  const int bad = predictRobot(P, x, p);
  if (bad >= 0) {
    throw InputError("", 0,
                     "hole '" + P.holes[static_cast<size_t>(bad)].id +
                         "': the compliance equilibrium does not converge at the identified "
                         "parameters");
  }
  LmState s;
  s.x = x;
  s.p = std::move(p);
  return s;
}

}  // namespace

std::vector<Eigen::VectorXd> residualsAt(const PredictionModel& m, const IdentificationResult& r,
                                         const std::vector<IdentificationHole>& holes,
                                         const IdentificationOptions& o) {
  validateHoles(holes);
  Problem P = makeProblem(m, holes, o);
  return inPlaneResiduals(P, stateAt(P, r));
}

std::vector<Vec3> rotationResidualsAt(const PredictionModel& m, const IdentificationResult& r,
                                      const std::vector<IdentificationHole>& holes,
                                      const IdentificationOptions& o) {
  validateHoles(holes);
  Problem P = makeProblem(m, holes, o);
  return rotationResiduals(P, stateAt(P, r));
}

GeometryCalibration cardGeometry(const PredictionModel& m) {
  return m.robot.card.calibration ? *m.robot.card.calibration : GeometryCalibration{};
}

PredictionModel withIdentification(const PredictionModel& m, const IdentificationResult& r,
                                   const std::optional<nc::ToolAttachment>& tool) {
  PredictionModel out = m;
  out.compliance = r.compliance;
  if (tool && r.tool_mass && r.tool_com) {
    nc::ToolAttachment t = *tool;
    t.mass = *r.tool_mass;
    t.com = *r.tool_com;
    out.model = nc::buildModel(m.robot.real_chain, t);
    out.model.gravity = m.model.gravity;
    out.model.tol_phi = m.model.tol_phi;
    out.model.max_iterations = m.model.max_iterations;
  }
  return out;
}

Vec3 predictedHolePosition(const PredictionModel& m, nc::Data& data, const Vec6& theta_cmd,
                           double diameter) {
  const ProcessAtDiameter* proc = processFor(m, diameter);
  const Vec6 offset = controllerOffset(m, data, theta_cmd);
  const nc::Deflection d = nc::predictDeflection(m.model, data, m.compliance, theta_cmd,
                                                 processLoads(m, proc), {}, offset);
  if (!d.converged || !d.position_converged) {
    throw InputError("", 0, "the compliance equilibrium does not converge at these joints");
  }
  const Vec3 mach =
      proc ? Vec3(proc->mach.delta_tool.x(), proc->mach.delta_tool.y(), 0.0) : Vec3::Zero();
  return d.T_real.translation() + d.T_nominal.linear() * mach;
}

// ---------------------------------------------------------------- verification

const char* measuredDecisionName(MeasuredDecision d) {
  switch (d) {
    case MeasuredDecision::kConformanceProven:
      return "conformance-proven";
    case MeasuredDecision::kNonConformanceProven:
      return "non-conformance-proven";
    case MeasuredDecision::kNoDecision:
      return "no-decision";
  }
  return "?";
}

MeasuredDecision measuredDecision(double e, double U_meas, double t) {
  const double half = 0.5 * t;
  if (e + U_meas <= half) return MeasuredDecision::kConformanceProven;
  if (e - U_meas > half) return MeasuredDecision::kNonConformanceProven;
  return MeasuredDecision::kNoDecision;
}

namespace {
/// u_robpos of a prediction's budget (m; 0 when absent).
double repeatabilityOf(const HolePrediction& p) {
  for (const BudgetTerm& b : p.budget) {
    if (std::string(b.name) == "robot_repeatability") return b.u;
  }
  return 0.0;
}
}  // namespace

double residualSigma(const HolePrediction& p, double u_measurement) {
  const double u_rep = repeatabilityOf(p);
  return std::sqrt(u_measurement * u_measurement + u_rep * u_rep + p.u_mach * p.u_mach);
}

VerificationInput verificationInput(const HolePrediction& p, const Pose& T_W_hole,
                                    const Vec3& p_W_measured, double u_measurement) {
  VerificationInput in;
  in.id = p.id;
  in.T_W_hole = T_W_hole;
  in.p_W_measured = p_W_measured;
  in.u_measurement = u_measurement;
  in.p_W_predicted = p.deflection.T_real.translation() + p.d_mach;
  const double u_rep = repeatabilityOf(p);
  in.cov_work = p.robdef_cov + (u_rep * u_rep + p.u_mach * p.u_mach) * Eigen::Matrix2d::Identity();
  in.U_work = p.U_work;
  in.tolerance = p.tolerance;
  return in;
}

HoleVerification verifyHole(const VerificationInput& in) {
  HoleVerification v;
  v.id = in.id;
  const Mat3 R = in.T_W_hole.linear();
  const Vec3 a = R.col(2);
  const Vec3 p_nom = in.T_W_hole.translation();
  const Vec3 e = in.p_W_measured - p_nom;
  const Vec3 d = in.p_W_predicted - p_nom;
  v.e_meas = Eigen::Vector2d(R.col(0).dot(e), R.col(1).dot(e));
  v.e_meas_norm = v.e_meas.norm();
  v.e_along = a.dot(e);
  v.d_pred = Eigen::Vector2d(R.col(0).dot(d), R.col(1).dot(d));
  v.d_pred_norm = v.d_pred.norm();
  v.r = v.e_meas - v.d_pred;
  v.r_norm = v.r.norm();
  v.e_meas_W = e - a.dot(e) * a;
  v.d_pred_W = d - a.dot(d) * a;
  v.U_work = in.U_work;
  const double u2 = in.u_measurement * in.u_measurement;
  v.U_region = radialCoverage(in.cov_work + u2 * Eigen::Matrix2d::Identity(), 0.95);
  v.inside = v.r_norm <= v.U_region;
  v.U_meas = kRadial95 * in.u_measurement;
  v.tolerance = in.tolerance;
  v.decision = measuredDecision(v.e_meas_norm, v.U_meas, in.tolerance);
  return v;
}

namespace {

MagnitudeStats magnitudes(const std::vector<double>& x) {
  MagnitudeStats s;
  if (x.empty()) return s;
  double sum = 0;
  double sum2 = 0;
  for (const double v : x) {
    sum += v;
    sum2 += v * v;
    s.max = std::max(s.max, v);
  }
  const double n = static_cast<double>(x.size());
  s.mean = sum / n;
  s.rms = std::sqrt(sum2 / n);
  return s;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double ma = 0;
  double mb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ma += a[i] / n;
    mb += b[i] / n;
  }
  double sab = 0;
  double saa = 0;
  double sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  const double tiny = 1e-30;
  if (a.size() < 2 || saa <= tiny || sbb <= tiny) return std::numeric_limits<double>::quiet_NaN();
  return sab / std::sqrt(saa * sbb);
}

}  // namespace

VerificationSummary summarizeVerification(const std::vector<HoleVerification>& holes,
                                          const Mat3& R_W_frame) {
  VerificationSummary s;
  s.holes = static_cast<int>(holes.size());
  std::vector<double> e;
  std::vector<double> d;
  std::vector<double> r;
  for (const HoleVerification& h : holes) {
    e.push_back(h.e_meas_norm);
    d.push_back(h.d_pred_norm);
    r.push_back(h.r_norm);
    s.inside += h.inside;
    s.conformance_proven += h.decision == MeasuredDecision::kConformanceProven;
    s.nonconformance_proven += h.decision == MeasuredDecision::kNonConformanceProven;
    s.no_decision += h.decision == MeasuredDecision::kNoDecision;
  }
  s.measured = magnitudes(e);
  s.predicted = magnitudes(d);
  s.residual = magnitudes(r);
  s.explained = s.measured.rms > 0 ? 1.0 - s.residual.rms / s.measured.rms : 0.0;
  s.coverage = s.holes ? static_cast<double>(s.inside) / s.holes : 0.0;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> pa;
    std::vector<double> ma;
    for (const HoleVerification& h : holes) {
      pa.push_back(R_W_frame.col(a).dot(h.d_pred_W));
      ma.push_back(R_W_frame.col(a).dot(h.e_meas_W));
    }
    s.correlation[a] = pearson(pa, ma);
  }
  return s;
}

// ---------------------------------------------------------------- test planning

namespace {

/// log det of an SPD matrix (−∞ when not positive definite).
double logDet(const MatrixXd& A) {
  if (A.rows() == 0) return 0.0;
  const Eigen::LLT<MatrixXd> llt(A);
  if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
  return 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
}

/// The IdentificationHoles of the admissible candidates (their predicted joints).
std::vector<IdentificationHole> plannedHoles(const PredictionModel& m,
                                             const std::vector<HoleRequest>& candidates,
                                             double sigma, std::vector<int>& index,
                                             TestPlan& plan) {
  PredictionData d(m);
  std::vector<IdentificationHole> holes;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const HolePrediction p = predictHole(m, d, candidates[i], nullptr);
    if (p.status != HoleStatus::kOk) {
      plan.rejected.push_back(static_cast<int>(i));
      plan.rejected_reason.push_back(p.reason);
      continue;
    }
    IdentificationHole h;
    h.id = candidates[i].id;
    h.theta_cmd = p.joints;
    h.T_W_hole = candidates[i].T_W_tcp;
    h.diameter = candidates[i].diameter;
    h.p_W_measured = candidates[i].T_W_tcp.translation();
    h.sigma = sigma;
    holes.push_back(h);
    index.push_back(static_cast<int>(i));
  }
  return holes;
}

/// Inverse of an SPD matrix.
MatrixXd spdInverse(const MatrixXd& A) {
  return A.ldlt().solve(MatrixXd::Identity(A.rows(), A.cols()));
}

/// log det of the 2×2 matrix S (−∞ unless det S > 0), det S by LU with partial pivoting: the
/// arithmetic of Eigen's PartialPivLU::determinant for a 2×2 matrix (row 1 becomes the pivot row
/// only when strictly larger in magnitude), without its allocation.
double logDet2(double a, double b, double c, double d) {
  double sign = 1.0;
  if (std::abs(c) > std::abs(a)) {
    std::swap(a, c);
    std::swap(b, d);
    sign = -1.0;
  }
  if (std::max(std::abs(a), std::abs(c)) != 0.0) c /= a;
  d -= c * b;
  const double det = sign * (a * d);
  return det > 0 ? std::log(det) : -std::numeric_limits<double>::infinity();
}
double logDet2(const MatrixXd& S) { return logDet2(S(0, 0), S(0, 1), S(1, 0), S(1, 1)); }

/// Work space of criterionGain, sized once per selection (no allocation per candidate).
struct GainScratch {
  MatrixXd Ji, Jn, W, Wn, S;
};

/// The two terms of the D_s criterion's gain (log det M − log det M_nn, nuisance = the last `nn`
/// columns) when the 2×n block Ji (rows 2i, 2i + 1 of J) is added: by the matrix determinant
/// lemma,
///   Δ = full − nuisance,  full = log det(I + Ji M⁻¹ Jiᵀ),  nuisance = log det(I + Ji,n M_nn⁻¹
///   Ji,nᵀ)
/// with M⁻¹ and M_nn⁻¹ computed once per step (no n×n factorisation per candidate), each product
/// into the scratch's matrices. nuisance ≥ 0, and both terms only shrink as M grows (M⁻¹ and
/// M_nn⁻¹ decrease in the Loewner order): `full` at any earlier step bounds Δ from above.
struct Gain {
  double full{0};
  double value{0};  ///< Δ = full − nuisance
};

Gain criterionGain(const MatrixXd& J, Eigen::Index i, const MatrixXd& Minv, const MatrixXd& Mnn_inv,
                   Eigen::Index nn, GainScratch& s) {
  s.Ji = J.middleRows(2 * i, 2);
  s.W.noalias() = s.Ji * Minv;
  s.S.noalias() = s.W * s.Ji.transpose();
  s.S(0, 0) += 1.0;
  s.S(1, 1) += 1.0;
  Gain g;
  g.full = logDet2(s.S);
  g.value = g.full;
  if (nn > 0) {
    s.Jn = s.Ji.rightCols(nn);
    s.Wn.noalias() = s.Jn * Mnn_inv;
    s.S.noalias() = s.Wn * s.Jn.transpose();
    s.S(0, 0) += 1.0;
    s.S(1, 1) += 1.0;
    g.value -= logDet2(s.S);
  }
  return g;
}

/// criterionGain of a 6-parameter criterion without nuisance (the joint-stiffness plan) on
/// fixed-size data: Ji the candidate's 2 rows (row-major, 12 doubles), Minv M⁻¹ (row-major).
/// Every sum runs over k in order, as Eigen's coefficient-based product of the dynamic 2×6 and
/// 6×6 matrices does: the same gain to the last bit, without copies of the rows.
Gain criterionGain6(const double* Ji, const std::array<double, 36>& Minv) {
  std::array<double, 12> W;  // Ji M⁻¹
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 6; ++c) {
      double a = Ji[6 * r] * Minv[c];
      for (int k = 1; k < 6; ++k) a += Ji[6 * r + k] * Minv[6 * k + c];
      W[static_cast<size_t>(6 * r + c)] = a;
    }
  }
  double S[2][2];  // W Jiᵀ
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 2; ++c) {
      double a = W[static_cast<size_t>(6 * r)] * Ji[6 * c];
      for (int k = 1; k < 6; ++k) a += W[static_cast<size_t>(6 * r + k)] * Ji[6 * c + k];
      S[r][c] = a;
    }
  }
  S[0][0] += 1.0;
  S[1][1] += 1.0;
  Gain g;
  g.full = logDet2(S[0][0], S[0][1], S[1][0], S[1][1]);
  g.value = g.full;
  return g;
}

/// Asks the cache for a candidate's 12 contiguous doubles (96 bytes: two lines at most) while
/// the one before is evaluated; the lazy greedy visits the candidates in no memory order.
inline void prefetchRows(const double* rows) {
#if defined(__GNUC__)
  __builtin_prefetch(rows);
  __builtin_prefetch(rows + 11);
#else
  (void)rows;
#endif
}

/// A candidate in the lazy greedy's heap: `bound` ≥ its gain at the current step (its `full`
/// term when last evaluated; −∞ stands for NaN).
struct Bounded {
  double bound;
  int index;
};

/// Heap order: the largest bound on top, the lower index first among equal bounds.
bool belowInHeap(const Bounded& a, const Bounded& b) {
  return a.bound < b.bound || (a.bound == b.bound && a.index > b.index);
}

/// Slack of the lazy greedy's stopping test: a bound computed at an earlier step may undercut a
/// fresh gain by rounding (M⁻¹ is recomputed each step, relative error ~ cond(M)·ε); candidates
/// whose bound is within this of the best fresh gain are evaluated again.
double lazySlack(double best_gain) { return 1e-6 * (1.0 + std::abs(best_gain)); }

/// Marks the candidates closer than `min_spacing` to `chosen` (and itself) as used. A candidate
/// used already or |Δx| ≥ min_spacing away is skipped (its computed norm is ≥ the computed |Δx|).
/// `by_x`: the candidates sorted by x (byX), so that only those within 2·min_spacing in x are
/// looked at (a superset of the |Δx| < min_spacing the test keeps, whatever the rounding).
void markNeighbours(const std::vector<Vec3>& p_W, const std::vector<int>& by_x, int chosen,
                    double min_spacing, std::vector<bool>& used) {
  const Vec3& c = p_W[static_cast<size_t>(chosen)];
  const auto x_of = [&](int k) { return p_W[static_cast<size_t>(k)].x(); };
  auto it = std::lower_bound(by_x.begin(), by_x.end(), c.x() - 2 * min_spacing,
                             [&](int k, double x) { return x_of(k) < x; });
  for (; it != by_x.end() && x_of(*it) <= c.x() + 2 * min_spacing; ++it) {
    const auto k = static_cast<size_t>(*it);
    if (used[k] || std::abs(p_W[k].x() - c.x()) >= min_spacing) continue;
    if ((p_W[k] - c).norm() < min_spacing) used[k] = true;
  }
  used[static_cast<size_t>(chosen)] = true;
}

/// The candidate indices sorted by x (markNeighbours' window).
std::vector<int> byX(const std::vector<Vec3>& p_W) {
  std::vector<int> order(p_W.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return p_W[static_cast<size_t>(a)].x() < p_W[static_cast<size_t>(b)].x();
  });
  return order;
}

/// One step of the lazy greedy: the candidate of the largest fresh gain (the lowest index among
/// equal gains — the choice of a scan over all candidates), or −1 when none is left. Pops the
/// heap's top, evaluates it with this step's M⁻¹, and stops once the top's bound is below the
/// best fresh gain (by more than lazySlack): the gains only shrink, so no candidate below can
/// win. The evaluated candidates go back with their fresh bounds.
/// `gain(i)`: candidate i's Gain at this step.
template <class GainOf, class Prefetch>
int lazyStep(const GainOf& gain, const Prefetch& prefetch, const std::vector<bool>& used,
             std::vector<Bounded>& heap, std::vector<Bounded>& evaluated) {
  int best = -1;
  double best_gain = -std::numeric_limits<double>::infinity();
  evaluated.clear();
  while (!heap.empty()) {
    const Bounded top = heap.front();
    if (!used[static_cast<size_t>(top.index)] && best >= 0 &&
        top.bound < best_gain - lazySlack(best_gain))
      break;
    std::pop_heap(heap.begin(), heap.end(), belowInHeap);
    heap.pop_back();
    if (used[static_cast<size_t>(top.index)]) continue;  // chosen or too close: gone for good
    if (!heap.empty()) prefetch(heap.front().index);     // likely the next one evaluated
    const Gain g = gain(top.index);
    if (g.value > best_gain || (g.value == best_gain && best >= 0 && top.index < best)) {
      best_gain = g.value;
      best = top.index;
    }
    evaluated.push_back(
        {std::isnan(g.full) ? -std::numeric_limits<double>::infinity() : g.full, top.index});
  }
  for (const Bounded& e : evaluated) {
    if (e.index == best) continue;
    heap.push_back(e);
    std::push_heap(heap.begin(), heap.end(), belowInHeap);
  }
  return best;
}

/// One step of the plain greedy: every candidate left evaluated with this step's M⁻¹; the largest
/// gain, the first candidate among equal gains, or −1 when none is left.
template <class GainOf>
int scanStep(const GainOf& gain, const std::vector<bool>& used) {
  int best = -1;
  double best_gain = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < used.size(); ++i) {
    if (used[i]) continue;
    const double g = gain(static_cast<int>(i)).value;
    if (g > best_gain) {
      best_gain = g;
      best = static_cast<int>(i);
    }
  }
  return best;
}

/// Expected σ per parameter, the unobservable robot parameters, and the predicted accuracy
/// before and after calibration over all candidates.
void planStatistics(const Problem& P, const MatrixXd& J, const MatrixXd& C, double sigma,
                    double ratio_limit, TestPlan& plan) {
  const int n = P.layout.n;
  const int nr = P.layout.reg >= 0 ? P.layout.reg : n;  // robot parameters
  plan.names = P.spec.name;
  plan.prior_sigma = P.spec.s0;
  plan.expected_sigma = C.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (int k = 0; k < nr; ++k) {
    if (plan.expected_sigma[k] > ratio_limit * P.spec.s0[k])
      plan.unobservable.push_back(P.spec.name[static_cast<size_t>(k)]);
  }
  const VectorXd prior = P.spec.s0.head(nr).cwiseAbs2();
  double after = 0;
  double before = 0;
  const Eigen::Index holes = J.rows() / 2;
  for (Eigen::Index i = 0; i < holes; ++i) {
    const MatrixXd Ji = J.middleRows(2 * i, 2) * sigma;  // m per unit parameter
    after += (Ji * C * Ji.transpose()).trace();
    const MatrixXd Jr = Ji.leftCols(nr);
    before += (Jr * prior.asDiagonal() * Jr.transpose()).trace();
  }
  plan.predicted_accuracy = holes > 0 ? std::sqrt(after / static_cast<double>(holes)) : 0.0;
  plan.prior_accuracy = holes > 0 ? std::sqrt(before / static_cast<double>(holes)) : 0.0;
}

}  // namespace

// Lazy greedy (Minoux) without nuisance: its choice is the one of a scan over all candidates with
// this step's M⁻¹ (each gain evaluated by the same arithmetic); with nuisance the D_s gain may
// grow (its nuisance term shrinks too) and `full` bounds it loosely: every step scans.
std::vector<int> greedyDOptimal(const MatrixXd& J, const VectorXd& s0, int count, Eigen::Index nn,
                                const std::vector<Vec3>& p_W, double min_spacing,
                                double& criterion) {
  MatrixXd M = s0.cwiseInverse().cwiseAbs2().asDiagonal();
  const auto value = [&](const MatrixXd& A) {
    return logDet(A) - (nn > 0 ? logDet(A.bottomRightCorner(nn, nn)) : 0.0);
  };
  const int candidates = static_cast<int>(J.rows() / 2);
  std::vector<int> chosen;
  std::vector<bool> used(static_cast<size_t>(candidates), false);
  std::vector<Bounded> heap;  // the lazy greedy's (nn = 0), all bounds +∞ (not evaluated yet)
  if (nn == 0) {
    heap.reserve(static_cast<size_t>(candidates));
    for (int i = 0; i < candidates; ++i)
      heap.push_back({std::numeric_limits<double>::infinity(), i});
    std::make_heap(heap.begin(), heap.end(), belowInHeap);
  }
  GainScratch scratch;
  std::vector<Bounded> evaluated;
  // the stiffness plan (6 parameters, no nuisance): each candidate's rows contiguous, gains in
  // fixed-size arithmetic (criterionGain6)
  const bool six = J.cols() == 6 && nn == 0;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J_rows;
  if (six) J_rows = J;
  std::array<double, 36> Minv6{};
  const std::vector<int> by_x = byX(p_W);
  for (int step = 0; step < count; ++step) {
    const MatrixXd Minv = spdInverse(M);
    const MatrixXd Mnn_inv = nn > 0 ? spdInverse(M.bottomRightCorner(nn, nn)) : MatrixXd();
    int best = -1;
    if (six) {
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) Minv6[static_cast<size_t>(6 * r + c)] = Minv(r, c);
      const auto rows = [&](int i) { return J_rows.data() + 12 * static_cast<size_t>(i); };
      best = lazyStep([&](int i) { return criterionGain6(rows(i), Minv6); },
                      [&](int i) { prefetchRows(rows(i)); }, used, heap, evaluated);
    } else {
      const auto gain = [&](int i) { return criterionGain(J, i, Minv, Mnn_inv, nn, scratch); };
      best = nn > 0 ? scanStep(gain, used)
                    : lazyStep(
                          gain, [](int) {}, used, heap, evaluated);
    }
    if (best < 0) break;
    markNeighbours(p_W, by_x, best, min_spacing, used);
    chosen.push_back(best);
    const MatrixXd Jb = J.middleRows(2 * static_cast<Eigen::Index>(best), 2);
    M += Jb.transpose() * Jb;
  }
  criterion = value(M);
  return chosen;
}

TestPlan planTest(const PredictionModel& m, const std::vector<HoleRequest>& candidates, int count,
                  const PlanOptions& o) {
  if (count < 1) throw InputError("", 0, "the test program needs at least one hole");
  TestPlan plan;
  std::vector<int> index;
  const std::vector<IdentificationHole> holes = plannedHoles(m, candidates, o.sigma, index, plan);
  if (static_cast<int>(holes.size()) < count) {
    throw InputError("", 0,
                     "only " + std::to_string(holes.size()) + " of " +
                         std::to_string(candidates.size()) + " candidate holes are reachable; " +
                         std::to_string(count) + " wanted");
  }
  IdentificationOptions io;
  io.compliance_prior_rel = o.compliance_prior_rel;
  io.registration = o.registration;
  io.T_W_wobj = o.T_W_wobj;
  io.translation_prior = o.translation_prior;
  io.rotation_prior = o.rotation_prior;
  io.relative_step = o.relative_step;
  io.geometry = o.geometry;
  Problem P = makeProblem(m, holes, io);
  const LmState prior = priorState(P);
  MatrixXd J;
  if (!dataJacobian(P, prior.x, prior.p, allColumns(P.layout.n), J)) {
    throw InputError(
        "", 0, "the compliance equilibrium fails near the card's stiffness at a candidate hole");
  }
  std::vector<Vec3> p_W;
  p_W.reserve(holes.size());
  for (const IdentificationHole& h : holes) p_W.push_back(h.T_W_hole.translation());
  const std::vector<int> chosen =
      greedyDOptimal(J, P.spec.s0, count, P.layout.n_reg, p_W, o.min_spacing, plan.log_det);
  if (static_cast<int>(chosen.size()) < count) {
    throw InputError("", 0,
                     "only " + std::to_string(chosen.size()) + " candidate holes are at least " +
                         std::to_string(std::lround(o.min_spacing * 1e3)) + " mm apart; " +
                         std::to_string(count) + " wanted (enlarge the region or use fewer holes)");
  }
  MatrixXd M = P.spec.s0.cwiseInverse().cwiseAbs2().asDiagonal();
  for (const int c : chosen) {
    plan.chosen.push_back(index[static_cast<size_t>(c)]);
    const MatrixXd Jc = J.middleRows(2 * static_cast<Eigen::Index>(c), 2);
    M += Jc.transpose() * Jc;
  }
  const MatrixXd C = spdInverse(M);
  planStatistics(P, J, C, o.sigma, o.identifiable_ratio, plan);
  if (o.geometry) {
    MatrixXd Jc(2 * static_cast<Eigen::Index>(chosen.size()), J.cols());
    for (size_t c = 0; c < chosen.size(); ++c)
      Jc.middleRows(2 * static_cast<Eigen::Index>(c), 2) =
          J.middleRows(2 * static_cast<Eigen::Index>(chosen[c]), 2);
    dependentNames(P, Jc, io.dependency_tolerance, plan.dependencies);
  }
  const Vec6 k = m.compliance.k;
  for (int j = 0; j < 6; ++j) {
    plan.prior_sigma_rel[j] = o.compliance_prior_rel[j];
    plan.expected_sigma_rel[j] = std::sqrt(C(j, j));
    plan.expected_sigma_k[j] = plan.expected_sigma_rel[j] * P.c0[j] * k[j] * k[j];
  }
  return plan;
}

std::vector<HoleRequest> planningCandidates(const Pose& T_W_wobj, const Vec3& lo, const Vec3& hi,
                                            int per_axis, const std::vector<Vec3>& directions,
                                            const std::vector<double>& psi) {
  std::vector<HoleRequest> out;
  const int n = std::max(1, per_axis);
  auto coord = [&](int a, int i) {
    if (n == 1 || lo[a] == hi[a]) return lo[a];
    return lo[a] + (hi[a] - lo[a]) * i / (n - 1);
  };
  const int nx = lo.x() == hi.x() ? 1 : n;
  const int ny = lo.y() == hi.y() ? 1 : n;
  const int nz = lo.z() == hi.z() ? 1 : n;
  for (int ix = 0; ix < nx; ++ix) {
    for (int iy = 0; iy < ny; ++iy) {
      for (int iz = 0; iz < nz; ++iz) {
        const Vec3 p(coord(0, ix), coord(1, iy), coord(2, iz));
        for (const Vec3& dir : directions) {
          const Vec3 z = dir.normalized();
          const Vec3 ref = std::abs(z.x()) > std::cos(26.0 * kDeg) ? Vec3::UnitY() : Vec3::UnitX();
          const Vec3 x = (ref - ref.dot(z) * z).normalized();
          Mat3 R;
          R << x, z.cross(x), z;
          for (const double a : psi) {
            HoleRequest h;
            char id[16];
            std::snprintf(id, sizeof id, "C%04d", static_cast<int>(out.size()) + 1);
            h.id = id;
            Pose T = Pose::Identity();
            T.linear() = R * Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
            T.translation() = p;
            h.T_W_tcp = T_W_wobj * T;
            out.push_back(h);
          }
        }
      }
    }
  }
  return out;
}

}  // namespace roprec
