#include "compensator/process/milling.hpp"
#include "compensator/process/milling_consistent.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <exception>
#include <unsupported/Eigen/FFT>

#include "compensator/support/quadrature.hpp"

namespace roprec {
namespace {

constexpr double kH0 = 1e-3;                 // Kienzle reference chip thickness
constexpr double kMaxFeedPerDiameter = 0.2;  // fz_eff above 0.2 D: out of the model's range

/// φ wrapped to [0, 2π).
double wrappedAngle(double phi) { return std::fmod(std::fmod(phi, 2 * kPi) + 2 * kPi, 2 * kPi); }

/// Whether a wrapped angle lies in the arc.
bool inArcWrapped(double wrapped, const ImmersionAngles& a) {
  return wrapped >= a.start && wrapped <= a.exit;
}

bool inArc(double phi, const ImmersionAngles& a) { return inArcWrapped(wrappedAngle(phi), a); }

Eigen::Vector2d radial(double phi) { return {std::sin(phi), std::cos(phi)}; }

Vec3 wallNormal(MillingMode mode) {
  switch (mode) {
    case MillingMode::kUp:
      return Vec3::UnitY();
    case MillingMode::kDown:
      return -Vec3::UnitY();
    case MillingMode::kSlot:
      break;
  }
  return Vec3::Zero();
}

}  // namespace

ImmersionAngles immersionAngles(double diameter, double ae, MillingMode mode) {
  if (mode == MillingMode::kSlot || ae >= diameter) return {0.0, kPi};
  const double arc = std::acos(std::clamp(1.0 - 2.0 * ae / diameter, -1.0, 1.0));
  if (mode == MillingMode::kUp) return {0.0, arc};
  return {kPi - arc, kPi};
}

double meanChipThickness(double fz, const ImmersionAngles& a) {
  const double span = a.exit - a.start;
  if (!(span > 0)) return 0.0;
  return fz * (std::cos(a.start) - std::cos(a.exit)) / span;
}

MillingModel makeMillingModel(const MillingTool& tool, const MillingCut& cut,
                              const MillingCoefficients& c, int angle_steps, int slices) {
  MillingModel m;
  m.tool = tool;
  m.cut = cut;
  m.coeff = c;
  m.angle_steps = angle_steps;
  m.slices = slices;
  const double R = 0.5 * tool.diameter;
  for (int j = 0; j < tool.teeth; ++j) {
    m.tooth_radius.push_back(R +
                             tool.runout * std::cos(tool.runout_angle - j * 2 * kPi / tool.teeth));
  }
  m.slice_height = cut.ap / slices;
  // Gauss–Legendre (Newton on P_n) for the arc average; 48 nodes keep the sin^0.75 end point
  // behaviour below 1e-4 relative.
  const int n = 48;
  gaussLegendre(n, m.gl_x, m.gl_w);
  for (int s = 0; s < slices; ++s) {
    const double z = (s + 0.5) * m.slice_height;
    m.slice_lag.push_back(z * std::tan(tool.helix_angle) / R);
  }
  return m;
}

double toothChipThickness(const MillingModel& m, int tooth, double phi, double fz,
                          const Eigen::Vector2d* deflection_history) {
  const int Nt = m.tool.teeth;
  const double s = std::sin(phi);
  const Eigen::Vector2d n = radial(phi);
  double h = 1e300;
  for (int k = 1; k <= Nt; ++k) {
    const int prev = ((tooth - k) % Nt + Nt) % Nt;
    double hk = k * fz * s + (m.tooth_radius[static_cast<size_t>(tooth)] -
                              m.tooth_radius[static_cast<size_t>(prev)]);
    if (deflection_history != nullptr) hk += (deflection_history[0] - deflection_history[k]).dot(n);
    h = std::min(h, hk);
  }
  return std::max(0.0, h);
}

MillingProfile millingForceProfile(const MillingModel& m) {
  MillingProfile P;
  const ImmersionAngles arc = immersionAngles(m.tool.diameter, m.cut.ae, m.cut.mode);
  const int Nt = m.tool.teeth;
  P.samples.resize(static_cast<size_t>(m.angle_steps));
  P.max_chip.assign(static_cast<size_t>(Nt), 0.0);
  const double e = 1.0 - m.coeff.mc;
  for (int i = 0; i < m.angle_steps; ++i) {
    const double angle = 2 * kPi * i / m.angle_steps;
    Vec3 F = Vec3::Zero();
    for (int j = 0; j < Nt; ++j) {
      for (int s = 0; s < m.slices; ++s) {
        const double phi = angle + j * 2 * kPi / Nt - m.slice_lag[static_cast<size_t>(s)];
        if (!inArc(phi, arc)) continue;
        const double h = toothChipThickness(m, j, phi, m.cut.fz);
        P.max_chip[static_cast<size_t>(j)] = std::max(P.max_chip[static_cast<size_t>(j)], h);
        if (h < m.coeff.h_min) continue;
        const double dFt = m.coeff.kc11 * m.slice_height * kH0 * std::pow(h / kH0, e);
        const double dFr = m.coeff.radial_ratio * dFt;
        const double c = std::cos(phi);
        const double sn = std::sin(phi);
        F.x() += -dFt * c - dFr * sn;
        F.y() += dFt * sn - dFr * c;
        F.z() += -m.coeff.axial_ratio * dFt;
      }
    }
    P.samples[static_cast<size_t>(i)] = {angle, F};
    P.mean += F;
    P.peak_xy = std::max(P.peak_xy, F.head<2>().norm());
  }
  P.mean /= m.angle_steps;
  return P;
}

namespace {

/// ∫ over [lo, hi] of the instantaneous law at the chip min_k (k fz sin φ + c[k−1]) by
/// Gauss–Legendre (the min is smooth in between: the caller splits at its kinks).
Vec3 arcIntegral(const MillingModel& m, double fz, const std::vector<double>& c, double lo,
                 double hi) {
  const double e = 1.0 - m.coeff.mc;
  const double cr = m.coeff.radial_ratio;
  const double half = 0.5 * (hi - lo);
  const double mid = 0.5 * (hi + lo);
  Vec3 F = Vec3::Zero();
  for (size_t i = 0; i < m.gl_x.size(); ++i) {
    const double phi = mid + half * m.gl_x[i];
    const double sn = std::sin(phi);
    double h = fz * sn + c[0];
    for (size_t k = 1; k < c.size(); ++k)
      h = std::min(h, static_cast<double>(k + 1) * fz * sn + c[k]);
    const double Ft = m.coeff.kc11 * m.cut.ap * kH0 * std::pow(h / kH0, e) * half * m.gl_w[i];
    const double cs = std::cos(phi);
    F += Vec3(-Ft * cs - cr * Ft * sn, Ft * sn - cr * Ft * cs, -m.coeff.axial_ratio * Ft);
  }
  return F;
}

/// Tooth j's share ∫ Ft(h_j)(…) dφ with h_j = min_k [k fz sin φ + R_j − R_{j−k}] (§4.3: what the
/// earlier teeth left), on the part of the arc where h_j ≥ h_min, split where the minimising k
/// changes.
Vec3 toothMeanForce(const MillingModel& m, int j, double fz, const ImmersionAngles& a) {
  const int Nt = m.tool.teeth;
  // the offsets and the arc's break points in buffers of the thread (no allocation per call)
  thread_local std::vector<double> c;
  thread_local std::vector<double> breaks;
  c.assign(static_cast<size_t>(Nt), 0.0);
  double smin = -1;  // h_j ≥ h_min ⇔ sin φ ≥ smin
  for (int k = 1; k <= Nt; ++k) {
    c[static_cast<size_t>(k - 1)] = m.tooth_radius[static_cast<size_t>(j)] -
                                    m.tooth_radius[static_cast<size_t>(((j - k) % Nt + Nt) % Nt)];
    smin = std::max(smin, (m.coeff.h_min - c[static_cast<size_t>(k - 1)]) / (k * fz));
  }
  if (smin > 1) return Vec3::Zero();
  const double cut = smin > 0 ? std::asin(smin) : 0.0;
  const double lo = std::max(a.start, cut);
  const double hi = std::min(a.exit, kPi - cut);
  if (!(hi > lo)) return Vec3::Zero();
  breaks.assign({lo, hi});
  for (int k1 = 1; k1 <= Nt; ++k1) {
    for (int k2 = k1 + 1; k2 <= Nt; ++k2) {
      const double sx =
          (c[static_cast<size_t>(k2 - 1)] - c[static_cast<size_t>(k1 - 1)]) / ((k1 - k2) * fz);
      if (!(sx > 0 && sx < 1)) continue;
      for (const double phi : {std::asin(sx), kPi - std::asin(sx)})
        if (phi > lo && phi < hi) breaks.push_back(phi);
    }
  }
  std::sort(breaks.begin(), breaks.end());
  Vec3 F = Vec3::Zero();
  for (size_t i = 1; i < breaks.size(); ++i)
    if (breaks[i] > breaks[i - 1]) F += arcIntegral(m, fz, c, breaks[i - 1], breaks[i]);
  return F;
}

/// (1/2π) Σ_j tooth j's share; without runout every tooth is tooth 0 (Nt/(2π) × its share).
Vec3 instantaneousMeanForce(const MillingModel& m, double fz, const ImmersionAngles& a) {
  if (m.tool.runout == 0) return toothMeanForce(m, 0, fz, a) * (m.tool.teeth / (2 * kPi));
  Vec3 F = Vec3::Zero();
  for (int j = 0; j < m.tool.teeth; ++j) F += toothMeanForce(m, j, fz, a);
  return F / (2 * kPi);
}

}  // namespace

Vec3 MeanForceMemo::operator()(const MillingModel& m, double fz, double ae) {
  ++clock_;
  for (Entry& e : entries_) {
    if (e.used != 0 && e.fz == fz && e.ae == ae) {
      e.used = clock_;
      return e.F;
    }
  }
  Entry* out = entries_.data();  // the least recently used
  for (Entry& e : entries_)
    if (e.used < out->used) out = &e;
  *out = Entry{fz, ae, millingMeanForce(m, fz, ae), clock_};
  return out->F;
}

void MeanForceMemo::reset() { *this = MeanForceMemo{}; }

Vec3 millingMeanForce(const MillingModel& m, double fz, double ae) {
  if (!(fz > 0) || !(ae > 0)) return Vec3::Zero();
  const ImmersionAngles a = immersionAngles(m.tool.diameter, ae, m.cut.mode);
  if (m.mean_law == MeanForceLaw::kInstantaneous) return instantaneousMeanForce(m, fz, a);
  const double hm = meanChipThickness(fz, a);
  if (hm < m.coeff.h_min) return Vec3::Zero();
  const double Ftm = m.coeff.kc11 * m.cut.ap * kH0 * std::pow(hm / kH0, 1.0 - m.coeff.mc);
  const double k = m.tool.teeth * Ftm / (2 * kPi);
  const double cr = m.coeff.radial_ratio;
  const double ds = std::sin(a.exit) - std::sin(a.start);
  const double dc = std::cos(a.start) - std::cos(a.exit);
  return {k * (-ds - cr * dc), k * (dc - cr * ds), -m.coeff.axial_ratio * k * (a.exit - a.start)};
}

ComplianceFunction linearCompliance(const Mat3& C_m_per_N) {
  return [C_m_per_N](const Vec3& f) -> Vec3 { return C_m_per_N * f; };
}

ComplianceFunction withToolCompliance(ComplianceFunction robot, const Mat3& C_tool) {
  return
      [robot = std::move(robot), C_tool](const Vec3& f) -> Vec3 { return robot(f) + C_tool * f; };
}

const char* couplingStatusName(CouplingStatus s) {
  switch (s) {
    case CouplingStatus::kConverged:
      return "converged";
    case CouplingStatus::kDiverged:
      return "diverged";
    case CouplingStatus::kMaxIterations:
      return "max_iterations";
    case CouplingStatus::kOutOfRange:
      return "out_of_range";
    case CouplingStatus::kNoDescent:
      return "no_descent";
    case CouplingStatus::kComplianceFailed:
      return "compliance_failed";
  }
  return "unknown";
}

const char* couplingMethodName(CouplingMethod m) {
  return m == CouplingMethod::kNewton ? "newton" : "fixed_point";
}

namespace {

struct CutAt {
  double fz{0}, ae{0}, ap{0};
  bool in_range{true};
};

CutAt cutAt(const MillingModel& m, const CouplingState& st, const CouplingOptions& o,
            const Vec3& d) {
  CutAt c;
  c.fz =
      m.cut.fz + (d.x() - st.delta_prev.x()) / std::max(1, o.teeth_between_points) + st.uncut_prev;
  const Vec3 n = wallNormal(m.cut.mode);
  c.ae = m.cut.mode == MillingMode::kSlot ? m.cut.ae : m.cut.ae + d.dot(n);
  if (c.ae > m.tool.diameter) {
    c.ae = m.tool.diameter;
    c.in_range = false;
  }
  if (c.fz > kMaxFeedPerDiameter * m.tool.diameter) c.in_range = false;
  c.ap = m.cut.ap - d.z();  // +Z lifts the tool out of the cut
  if (c.ap > 2 * m.cut.ap) c.in_range = false;
  return c;
}

/// F̄ is linear in ap: the mean force at the cut's ap scaled to the effective one.
Vec3 forceAt(const MillingModel& m, const CutAt& c, MeanForceMemo& memo) {
  if (c.fz <= 0 || c.ae <= 0 || c.ap <= 0) return Vec3::Zero();
  return memo(m, c.fz, c.ae) * (c.ap / m.cut.ap);
}
Vec3 forceAt(const MillingModel& m, const CutAt& c) {
  MeanForceMemo memo;
  return forceAt(m, c, memo);
}

/// The force law of the solve: F̄ plus a constant correction ΔF while the tool cuts (the
/// edge-consistent solve's dynamic part, coupleMillingPointConsistent; zero otherwise).
Vec3 forceAt(const MillingModel& m, const CutAt& c, const Vec3& correction, MeanForceMemo& memo) {
  const Vec3 F = forceAt(m, c, memo);
  return F.isZero() ? F : Vec3(F + correction);
}

/// Thrown by the evaluator when the compliance fails or returns a non-finite value.
struct ComplianceFailure {};

/// The map δ ↦ C(F(δ)) of one path point, counting the compliance calls.
class CoupledMap {
 public:
  CoupledMap(const MillingModel& m, const ComplianceFunction& C, const CouplingState& st,
             const CouplingOptions& o, const Vec3& correction, MeanForceMemo& memo)
      : m_(m), C_(C), st_(st), o_(o), correction_(correction), memo_(memo) {}
  Vec3 image(const Vec3& d) {
    ++evaluations;
    Vec3 out;
    try {
      out = C_(force(cutAt(m_, st_, o_, d)));
    } catch (const std::exception&) {
      throw ComplianceFailure{};
    }
    if (!out.allFinite()) throw ComplianceFailure{};
    return out;
  }
  Vec3 residual(const Vec3& d) { return d - image(d); }
  /// The solve's force law at the cut c (forceAt, through the map's memo), and F̄ alone.
  Vec3 force(const CutAt& c) { return forceAt(m_, c, correction_, memo_); }
  Vec3 staticForce(const CutAt& c) { return forceAt(m_, c, memo_); }
  /// G = ∂(C∘F)/∂δ by forward differences (step h) around d, whose image is `image_d`.
  Mat3 gain(const Vec3& d, const Vec3& image_d) {
    constexpr double h = 1e-6;
    Mat3 G;
    for (int i = 0; i < 3; ++i) {
      Vec3 e = Vec3::Zero();
      e[i] = h;
      G.col(i) = (image(d + e) - image_d) / h;
    }
    return G;
  }
  int evaluations{0};

 private:
  const MillingModel& m_;
  const ComplianceFunction& C_;
  const CouplingState& st_;
  const CouplingOptions& o_;
  Vec3 correction_;
  MeanForceMemo& memo_;
};

double spectralRadius(const Mat3& G) {
  if (!G.allFinite()) return 0.0;
  const Eigen::EigenSolver<Mat3> es(G, false);
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

/// The Newton direction −J⁻¹r (J = I − G); the plain fixed-point step −r when J is singular.
Vec3 newtonDirection(const Mat3& G, const Vec3& r) {
  const Mat3 J = Mat3::Identity() - G;
  const Eigen::ColPivHouseholderQR<Mat3> qr(J);
  if (qr.rank() == 3) {
    Vec3 p = -qr.solve(r);
    if (p.allFinite()) return p;
  }
  return -r;
}

/// Newton with backtracking line search on |r|: converges whatever the loop gain. A warm start
/// (options.start_gain) takes its first step with the given G.
void solveNewton(CoupledMap& map, const CouplingOptions& o, Vec3& d, CouplingResult& res) {
  Vec3 Cd = map.image(d);
  Vec3 r = d - Cd;
  double norm = r.norm();
  // a step along p, halved until it lowers |r| (Armijo)
  const auto lineSearch = [&](const Vec3& p) {
    double alpha = 1.0;
    for (int ls = 0; ls <= 30; ++ls, alpha *= 0.5) {
      const Vec3 dt = d + alpha * p;
      const Vec3 Ct = map.image(dt);
      const double nt = (dt - Ct).norm();
      if (nt <= (1.0 - 1e-4 * alpha) * norm) {
        res.step = alpha * p.norm();
        d = dt;
        Cd = Ct;
        r = d - Cd;
        norm = nt;
        return true;
      }
    }
    return false;
  };
  res.status = CouplingStatus::kMaxIterations;
  // a warm start's solve goes on to |r| <= tolerance / 10⁴ (or until no step lowers |r|): chord
  // steps with the given G while each lowers |r| tenfold, then finite-difference Newton steps
  const bool warm = o.start_gain.has_value();
  const double target = warm ? 1e-4 * o.tolerance : o.tolerance;
  bool chord = warm;
  for (int k = 0;; ++k) {
    if (norm <= target) {
      res.status = CouplingStatus::kConverged;
      break;
    }
    if (k >= o.max_iterations) {
      if (norm <= o.tolerance) res.status = CouplingStatus::kConverged;
      break;
    }
    if (chord) {
      const double before = norm;
      if (lineSearch(newtonDirection(*o.start_gain, r))) {
        res.iterations = k + 1;
        chord = norm <= 0.1 * before;
        continue;
      }
      chord = false;
    }
    res.iterations = k + 1;
    // Newton direction first; if no step along it lowers |r| (a kink of F: the chip or the
    // engagement reaching zero), the plain fixed-point direction −r.
    if (!lineSearch(newtonDirection(map.gain(d, Cd), r)) && !lineSearch(-r)) {
      // nothing lower than a converged |r| (a warm start's refinement): converged as it is
      res.status = norm <= o.tolerance ? CouplingStatus::kConverged : CouplingStatus::kNoDescent;
      break;
    }
  }
  res.residual = norm;
}

/// The plain (under-relaxed) iteration, kept for comparison: stops when |Δδ| ≤ tolerance, reports
/// divergence when the step grows 3 times in a row.
void solveFixedPoint(CoupledMap& map, const CouplingOptions& o, Vec3& d, CouplingResult& res) {
  const double omega = std::clamp(o.relaxation, 1e-3, 1.0);
  double last = 1e300;
  int growing = 0;
  res.status = CouplingStatus::kMaxIterations;
  for (int k = 1; k <= o.max_iterations; ++k) {
    const Vec3 d_new = (1.0 - omega) * d + omega * map.image(d);
    res.step = (d_new - d).norm();
    d = d_new;
    res.iterations = k;
    if (res.step <= o.tolerance) {
      res.status = CouplingStatus::kConverged;
      break;
    }
    growing = res.step >= last ? growing + 1 : 0;
    last = res.step;
    if (growing >= 3 || !d.allFinite() || d.norm() > 1.0) {
      res.status = CouplingStatus::kDiverged;
      break;
    }
  }
  res.residual = d.allFinite() ? map.residual(d).norm() : 0.0;
}

}  // namespace

namespace {

/// coupleMillingPoint with the force law F̄ + ΔF (forceAt with a correction).
CouplingResult couplePoint(const MillingModel& m, const ComplianceFunction& compliance,
                           const CouplingState& state, const CouplingOptions& o,
                           const Vec3& correction, MeanForceMemo* shared_memo = nullptr) {
  CouplingResult r;
  MeanForceMemo own;
  CoupledMap map(m, compliance, state, o, correction, shared_memo ? *shared_memo : own);
  r.force_nominal = map.staticForce(CutAt{m.cut.fz + state.uncut_prev, m.cut.ae, m.cut.ap, true});
  Vec3 d = Vec3::Zero();
  try {
    // first iterate: the warm start's, or the deflection under the nominal force
    const bool warm = o.method == CouplingMethod::kNewton && o.start && o.start_gain;
    d = warm ? *o.start : map.image(Vec3::Zero());
    if (o.method == CouplingMethod::kNewton) {
      CouplingOptions ow = o;
      if (!warm) ow.start_gain.reset();
      solveNewton(map, ow, d, r);
    } else {
      // a diverged plain iteration ends where the tool left the cut (G = 0): the gain at the
      // nominal cut (δ = 0) is the informative one
      r.loop_gain = spectralRadius(map.gain(Vec3::Zero(), d));
      solveFixedPoint(map, o, d, r);
    }
    if (!d.allFinite()) {
      d = Vec3::Zero();
      r.status = CouplingStatus::kDiverged;
    }
    if (o.loop_gain || o.method != CouplingMethod::kNewton) {
      const Vec3 Cd = map.image(d);
      const Mat3 G = map.gain(d, Cd);
      r.gain = G;
      r.loop_gain = std::max(r.loop_gain, spectralRadius(G));
    }
  } catch (const ComplianceFailure&) {
    r.status = CouplingStatus::kComplianceFailed;
    if (!d.allFinite()) d = Vec3::Zero();
  }
  if (!std::isfinite(r.residual)) r.residual = 0.0;
  if (!std::isfinite(r.step)) r.step = 0.0;
  const CutAt c = cutAt(m, state, o, d);
  if (r.status == CouplingStatus::kConverged && !c.in_range) r.status = CouplingStatus::kOutOfRange;
  r.converged = r.status == CouplingStatus::kConverged;
  r.evaluations = map.evaluations;
  r.delta = d;
  r.force = map.force(c);
  r.fz_effective = c.fz;
  r.ae_effective = c.ae;
  r.ap_effective = c.ap;
  r.next.delta_prev = d;
  r.next.uncut_prev = c.fz < 0 ? c.fz : 0.0;
  return r;
}

}  // namespace

CouplingResult coupleMillingPoint(const MillingModel& m, const ComplianceFunction& compliance,
                                  const CouplingState& state, const CouplingOptions& o,
                                  MeanForceMemo* memo) {
  return couplePoint(m, compliance, state, o, Vec3::Zero(), memo);
}

double couplingLoopGain(const MillingModel& m, const ComplianceFunction& compliance,
                        const CouplingState& state, const CouplingOptions& o,
                        const CouplingResult& r, MeanForceMemo* memo) {
  if (o.method != CouplingMethod::kNewton) return r.loop_gain;  // computed by the solve
  if (r.status == CouplingStatus::kComplianceFailed) return 0.0;
  MeanForceMemo own;
  CoupledMap map(m, compliance, state, o, Vec3::Zero(), memo ? *memo : own);
  try {
    return spectralRadius(map.gain(r.delta, map.image(r.delta)));
  } catch (const ComplianceFailure&) {
    return 0.0;
  }
}

ConsistentCoupling coupleMillingPointConsistent(const MillingModel& m,
                                                const ComplianceFunction& compliance,
                                                const EdgeRevolutionFunction& edges,
                                                const CouplingState& state,
                                                const CouplingOptions& o,
                                                const Vec3& start_correction) {
  ConsistentCoupling out;
  Vec3 correction = start_correction;
  for (out.rounds = 1; out.rounds <= kConsistencyRounds; ++out.rounds) {
    out.point = couplePoint(m, compliance, state, o, correction);
    out.correction = correction;
    if (!out.point.converged) return out;
    const CouplingResult& p = out.point;
    out.edges = edges(p.fz_effective, p.ae_effective, p.ap_effective);
    Vec3 image;
    try {
      image = compliance(out.edges.mean);
    } catch (const std::exception&) {
      out.point.converged = false;
      out.point.status = CouplingStatus::kComplianceFailed;
      return out;
    }
    if (!image.allFinite()) {
      out.point.converged = false;
      out.point.status = CouplingStatus::kComplianceFailed;
      return out;
    }
    out.edge_residual = (p.delta - image).norm();
    if (out.edge_residual <= o.tolerance) {
      out.consistent = true;
      out.point.force = out.edges.mean;
      return out;
    }
    const Vec3 F_static = forceAt(m, cutAt(m, state, o, p.delta));  // zero out of the cut
    correction = F_static.isZero() ? Vec3::Zero() : Vec3(out.edges.mean - F_static);
  }
  out.rounds = kConsistencyRounds;
  return out;
}

namespace {

/// The receptance at the harmonics k = 1..kmax of the spindle frequency (k = 0 unused).
std::vector<Mat3c> harmonicReceptances(const ModalModel& dyn, double spindle_rpm, size_t kmax) {
  std::vector<Mat3c> H(kmax + 1, Mat3c::Zero());
  const double Omega = 2 * kPi * spindle_rpm / 60.0;
  for (size_t k = 1; k <= kmax && !dyn.modes.empty(); ++k)
    H[k] = receptance(dyn, static_cast<double>(k) * Omega);
  return H;
}

/// x_dyn from the force samples through the harmonic receptances: the same sum as
/// milling_dynamics.hpp periodicResponse,
///   x[n] = Σ_{k=1..K} 2 Re[H_k F_k e^{+i2πkn/N}],   F_k = (1/N) Σ_n F[n] e^{−i2πkn/N},
/// with both transforms taken by FFT (O(N log N) an iteration instead of O(N·K)) and the
/// receptances computed once.
class HarmonicResponse {
 public:
  HarmonicResponse(std::vector<Mat3c> H, size_t N) : H_(std::move(H)), N_(N) {
    fft_.SetFlag(Eigen::FFT<double>::Unscaled);
    for (int c = 0; c < 3; ++c) {
      spectrum_[c].assign(N_, {0.0, 0.0});
      response_[c].assign(N_, {0.0, 0.0});
    }
    samples_.resize(N_);
    back_.resize(N_);
  }
  void operator()(const std::vector<Vec3>& force, std::vector<Vec3>& x) {
    for (int c = 0; c < 3; ++c) {
      for (size_t n = 0; n < N_; ++n) samples_[n] = force[n][c];
      fft_.fwd(spectrum_[c].data(), samples_.data(), static_cast<Eigen::Index>(N_));
    }
    for (size_t k = 1; k < H_.size(); ++k) {
      const Eigen::Vector3cd Fk(spectrum_[0][k], spectrum_[1][k], spectrum_[2][k]);
      const Eigen::Vector3cd Xk = H_[k] * (Fk / static_cast<double>(N_));
      for (int c = 0; c < 3; ++c) {
        response_[c][k] = Xk(c);
        response_[c][N_ - k] = std::conj(Xk(c));
      }
    }
    for (int c = 0; c < 3; ++c) {
      fft_.inv(back_.data(), response_[c].data(), static_cast<Eigen::Index>(N_));
      for (size_t n = 0; n < N_; ++n) x[n][c] = back_[n].real();
    }
  }

 private:
  std::vector<Mat3c> H_;  ///< k = 0..K (k = 0 unused); K < N/2
  size_t N_;
  Eigen::FFT<double> fft_;
  std::array<std::vector<std::complex<double>>, 3> spectrum_, response_;  ///< k = 0..N−1
  std::vector<double> samples_;
  std::vector<std::complex<double>> back_;
};

/// The cut a revolution is resolved at.
struct EdgeCut {
  double fz, ae, ap;
  int per;  ///< samples per tooth
};

/// The cutter's geometry over the revolution, the same at every iteration: for each sample n,
/// tooth j and slice s, the edge angle φ wrapped to [0, 2π) (what inArc compares) with its sine and
/// cosine; the samples the earlier passes cut at; the teeth's radius steps.
struct EdgeGeometry {
  std::vector<double> wrapped, sine, cosine;  ///< index (n·Nt + j)·slices + s
  std::vector<size_t> earlier;      ///< index n·Nt + (k − 1): sample n − k·per mod N
  std::vector<double> radius_step;  ///< index j·Nt + (k − 1): R_j − R_{j−k}
};
EdgeGeometry edgeGeometry(const MillingModel& m, const EdgeCut& c, int N) {
  const int Nt = m.tool.teeth;
  EdgeGeometry g;
  const size_t count = static_cast<size_t>(N) * static_cast<size_t>(Nt * m.slices);
  g.wrapped.reserve(count);
  g.sine.reserve(count);
  g.cosine.reserve(count);
  for (int n = 0; n < N; ++n) {
    const double angle = 2 * kPi * n / N;
    for (int j = 0; j < Nt; ++j)
      for (int s = 0; s < m.slices; ++s) {
        const double phi = angle + j * 2 * kPi / Nt - m.slice_lag[static_cast<size_t>(s)];
        g.wrapped.push_back(wrappedAngle(phi));
        g.sine.push_back(std::sin(phi));
        g.cosine.push_back(std::cos(phi));
      }
    for (int k = 1; k <= Nt; ++k)
      g.earlier.push_back(static_cast<size_t>(((n - k * c.per) % N + N) % N));
  }
  for (int j = 0; j < Nt; ++j)
    for (int k = 1; k <= Nt; ++k)
      g.radius_step.push_back(m.tooth_radius[static_cast<size_t>(j)] -
                              m.tooth_radius[static_cast<size_t>(((j - k) % Nt + Nt) % Nt)]);
  return g;
}

/// One pass over the revolution: the forces under the vibration x (see edgeRevolution), and,
/// when `out` is given, the per-tooth chips.
void edgeForces(const MillingModel& m, const EdgeCut& c, const EdgeGeometry& g,
                const std::vector<Vec3>& x, std::vector<Vec3>& F, EdgeRevolution* out) {
  const int Nt = m.tool.teeth;
  const int N = static_cast<int>(x.size());
  const double e = 1.0 - m.coeff.mc;
  const Vec3 wall = wallNormal(m.cut.mode);
  const ImmersionAngles static_arc = immersionAngles(m.tool.diameter, c.ae, m.cut.mode);
  std::vector<double> area(static_cast<size_t>(Nt), 0.0);
  std::vector<double> norm(static_cast<size_t>(Nt), 0.0);
  size_t at = 0;  // (n·Nt + j)·slices + s
  for (int n = 0; n < N; ++n) {
    const Vec3& xn = x[static_cast<size_t>(n)];
    const double ae_t = m.cut.mode == MillingMode::kSlot ? c.ae : c.ae + xn.dot(wall);
    const ImmersionAngles arc = immersionAngles(m.tool.diameter, ae_t, m.cut.mode);
    const double dz = std::max(0.0, c.ap - xn.z()) / m.slices;
    const size_t* earlier = &g.earlier[static_cast<size_t>(n * Nt)];
    Vec3 Fn = Vec3::Zero();
    if (!(ae_t > 0)) at += static_cast<size_t>(Nt * m.slices);
    for (int j = 0; j < Nt && ae_t > 0; ++j) {
      const double* radius_step = &g.radius_step[static_cast<size_t>(j * Nt)];
      for (int s = 0; s < m.slices; ++s, ++at) {
        const double sn = g.sine[at];
        if (out != nullptr && inArcWrapped(g.wrapped[at], static_arc))
          norm[static_cast<size_t>(j)] += sn;
        if (!inArcWrapped(g.wrapped[at], arc)) continue;
        const double cs = g.cosine[at];
        double h = 1e300;
        for (int k = 1; k <= Nt; ++k) {
          const Vec3& xp = x[earlier[k - 1]];
          h = std::min(h, k * c.fz * sn + radius_step[k - 1] + (xn.x() - xp.x()) * sn +
                              (xn.y() - xp.y()) * cs);
        }
        h = std::max(0.0, h);
        if (out != nullptr) {
          area[static_cast<size_t>(j)] += h;
          out->max_chip[static_cast<size_t>(j)] =
              std::max(out->max_chip[static_cast<size_t>(j)], h);
        }
        if (h < m.coeff.h_min) continue;
        const double dFt = m.coeff.kc11 * dz * kH0 * std::pow(h / kH0, e);
        const double dFr = m.coeff.radial_ratio * dFt;
        Fn += Vec3(-dFt * cs - dFr * sn, dFt * sn - dFr * cs, -m.coeff.axial_ratio * dFt);
      }
    }
    F[static_cast<size_t>(n)] = Fn;
  }
  if (out == nullptr) return;
  for (int j = 0; j < Nt; ++j) {
    const size_t u = static_cast<size_t>(j);
    out->tooth_feed[u] = norm[u] > 0 ? area[u] / norm[u] : 0.0;
  }
}

}  // namespace

EdgeRevolution edgeRevolution(const MillingModel& m, const ModalModel& dynamics, double fz,
                              double ae, double ap, const EdgeRevolutionOptions& o) {
  const int Nt = m.tool.teeth;
  const EdgeCut c{std::max(0.0, fz), std::clamp(ae, 0.0, m.tool.diameter), std::max(0.0, ap),
                  std::max(2, o.samples_per_tooth)};
  const size_t N = static_cast<size_t>(Nt * c.per);
  EdgeRevolution r;
  r.angle.resize(N);
  for (size_t n = 0; n < N; ++n) r.angle[n] = 2 * kPi * static_cast<double>(n) / N;
  r.force.assign(N, Vec3::Zero());
  r.vibration.assign(N, Vec3::Zero());
  r.tooth_feed.assign(static_cast<size_t>(Nt), 0.0);
  r.max_chip.assign(static_cast<size_t>(Nt), 0.0);
  HarmonicResponse response(harmonicReceptances(dynamics, m.cut.spindle_rpm, (N - 1) / 2), N);
  const EdgeGeometry geometry = edgeGeometry(m, c, static_cast<int>(N));
  std::vector<Vec3> next(N, Vec3::Zero());
  constexpr double kSmallestOmega = 1.0 / 64;
  double omega = std::clamp(o.relaxation, kSmallestOmega, 1.0);
  double last = 1e300;
  int growing = 0;  // the updates in a row larger than the one before
  r.converged = dynamics.modes.empty();
  for (int it = 1; !r.converged && it <= o.max_iterations; ++it) {
    edgeForces(m, c, geometry, r.vibration, r.force, nullptr);
    response(r.force, next);
    double update = 0;
    for (size_t n = 0; n < N; ++n) update = std::max(update, (next[n] - r.vibration[n]).norm());
    if (!std::isfinite(update)) break;
    growing = update > last ? growing + 1 : 0;
    if (update > last) omega = std::max(omega * 0.5, kSmallestOmega);
    last = update;
    r.iterations = it;
    r.update = update;
    if (update <= o.tolerance) {
      r.vibration = next;
      r.converged = true;
      break;
    }
    for (size_t n = 0; n < N; ++n) r.vibration[n] += omega * (next[n] - r.vibration[n]);
    if (omega == kSmallestOmega && growing >= o.diverging_iterations) break;  // it diverges
  }
  if (!r.converged) {
    // no periodic cut (past the chatter limit, or not settled): the vibration of the last
    // iterate, bounded; the caller reports the status
    for (Vec3& v : r.vibration)
      if (!v.allFinite()) v = Vec3::Zero();
  }
  edgeForces(m, c, geometry, r.vibration, r.force, &r);
  for (const Vec3& F : r.force) {
    r.mean += F;
    r.peak_xy = std::max(r.peak_xy, F.head<2>().norm());
  }
  r.mean /= static_cast<double>(N);
  return r;
}

CorrectedRevolution correctedRevolution(const MillingModel& m, const ModalModel& dynamics,
                                        const CouplingResult& point) {
  CorrectedRevolution out;
  EdgeRevolutionOptions o;
  o.samples_per_tooth = (m.angle_steps + m.tool.teeth - 1) / m.tool.teeth;
  out.nominal_edges = edgeRevolution(m, ModalModel{}, m.cut.fz, m.cut.ae, m.cut.ap, o);
  out.corrected_edges =
      edgeRevolution(m, dynamics, point.fz_effective, point.ae_effective, point.ap_effective, o);
  const EdgeRevolution& nom = out.nominal_edges;
  const EdgeRevolution& cor = out.corrected_edges;
  double lo = 1e300;
  double hi = 0;
  Vec3 xlo = Vec3::Constant(1e300);
  Vec3 xhi = Vec3::Constant(-1e300);
  for (size_t i = 0; i < nom.angle.size(); ++i) {
    CorrectedSample s;
    s.angle = nom.angle[i];
    s.nominal = nom.force[i];
    s.corrected = cor.force[i];
    s.tcp_movement = point.delta + cor.vibration[i];
    lo = std::min(lo, s.tcp_movement.norm());
    hi = std::max(hi, s.tcp_movement.norm());
    xlo = xlo.cwiseMin(cor.vibration[i]);
    xhi = xhi.cwiseMax(cor.vibration[i]);
    out.samples.push_back(s);
  }
  out.mean_nominal = nom.mean;
  out.mean_corrected = cor.mean;
  out.peak_nominal_xy = nom.peak_xy;
  out.peak_corrected_xy = cor.peak_xy;
  out.movement_range = out.samples.empty() ? 0.0 : hi - lo;
  if (!out.samples.empty()) out.vibration_peak_to_peak = xhi - xlo;
  return out;
}

std::vector<CouplingResult> coupleMillingPath(
    const MillingModel& m, const std::vector<ComplianceFunction>& compliance_per_point,
    const CouplingOptions& options) {
  std::vector<CouplingResult> out;
  out.reserve(compliance_per_point.size());
  CouplingState st;
  for (const ComplianceFunction& C : compliance_per_point) {
    out.push_back(coupleMillingPoint(m, C, st, options));
    st = out.back().next;
  }
  return out;
}

}  // namespace roprec
