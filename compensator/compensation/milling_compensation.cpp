#include "compensator/compensation/milling_compensation.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>

#include "compensator/precision/parallel.hpp"
#include "compensator/process/milling_mode_coupling.hpp"
#include "compensator/process/milling_robot.hpp"
#include "compensator/process/milling_stability.hpp"
#include "compensator/support/c_format.hpp"

namespace roprec {

namespace {
/// milling frame (X feed = tool x, Z = −tool z, Y = −tool y) ↔ tool frame
Vec3 millToTool(const Vec3& v) { return Vec3(v.x(), -v.y(), -v.z()); }

std::string fmt(double v, int decimals) { return cFixed(v, decimals); }
std::string mm(double v_m) { return fmt(v_m * 1e3, 3); }

/// The last chatter check along the path: reused while the robot's modes stay within
/// kModeReuseTolerance of those it was computed with (they change slowly along a path; the limit
/// moves about as much as the modes do).
struct StabilityCache {
  ModalModel modes;
  StabilityLimit limit;
  bool valid{false};
};
constexpr double kModeReuseTolerance = 0.005;

bool sameModes(const ModalModel& a, const ModalModel& b) {
  if (a.modes.size() != b.modes.size()) return false;
  for (size_t r = 0; r < a.modes.size(); ++r) {
    const VibrationMode& x = a.modes[r];
    const VibrationMode& y = b.modes[r];
    if (std::abs(x.omega - y.omega) > kModeReuseTolerance * y.omega) return false;
    // the mode's TCP vector up to its sign
    const double d = std::min((x.tcp - y.tcp).norm(), (x.tcp + y.tcp).norm());
    if (d > kModeReuseTolerance * y.tcp.norm()) return false;
  }
  return true;
}

/// The cell's model with the engagement's ae and ap (the slices and helix lags follow ap).
MillingModel engagedModel(const MillingModel& cell, const MillingEngagement& e) {
  MillingCut cut = cell.cut;
  cut.ae = e.ae;
  cut.ap = e.ap;
  MillingModel m = makeMillingModel(cell.tool, cut, cell.coeff, cell.angle_steps, cell.slices);
  m.mean_law = cell.mean_law;
  return m;
}

/// The robot's modes at θ_d and the spindle/tool mode; none when the pose has no modes.
std::optional<ModalModel> pointModes(const PredictionModel& m, PathPointCompensation& p) {
  const MillingSpec& s = m.process.milling;
  ModalModel dyn;
  try {
    dyn = robotModes(m.model, m.compliance, p.theta_d, s.robot_damping_ratio);
  } catch (const std::runtime_error&) {
    return std::nullopt;  // no modes at this pose: not checked
  }
  if (!dyn.modes.empty()) p.first_mode_hz = dyn.modes.front().omega / (2 * kPi);
  addToolMode(dyn, s.tool_mode);
  return dyn;
}

/// The zero-order stability limit with the modes `dyn` into `p`.
void checkStability(const ModalModel& dyn, const StabilityCut& cut, double spindle_rpm,
                    StabilityCache& cache, PathPointCompensation& p) {
  if (!cache.valid || !sameModes(dyn, cache.modes)) {
    cache.limit = limitingDepth(dyn, cut, spindle_rpm);
    cache.modes = dyn;
    cache.valid = true;
  }
  p.stability_checked = true;
  p.stability_bounded = cache.limit.bounded;
  p.ap_limit = cache.limit.ap_lim;
  p.chatter_hz = cache.limit.chatter_hz;
}

/// The last mode-coupling limit along the path and the modes it was computed with (reused with
/// the stability's rule).
struct ModeCouplingCache {
  ModalModel modes;
  ModeCouplingLimit limit;
  bool valid{false};
};

/// The mode-coupling limit of the point's cut (the engagement's fz, ae, ap) with the modes `dyn`
/// into `p`.
void checkModeCoupling(const MillingModel& mm, const ModalModel& dyn, ModeCouplingCache& cache,
                       PathPointCompensation& p) {
  if (!cache.valid || !sameModes(dyn, cache.modes)) {
    const ProcessGradient g = processGradient(mm, mm.cut.fz, mm.cut.ae, mm.cut.ap);
    cache.limit = modeCouplingLimit(dyn, g, mm.cut.ap);
    cache.modes = dyn;
    cache.valid = true;
  }
  p.mode_coupling_checked = true;
  p.mode_coupling_bounded = cache.limit.bounded;
  p.mode_coupling_ap_limit = cache.limit.ap_lim;
  p.mode_coupling_hz = cache.limit.frequency_hz;
  p.mode_coupling_flutter = cache.limit.flutter;
}

/// The wall's normal into the material in the base frame (milling frame ±Y: up +Y, down −Y; none
/// for a slot, which has a wall on each side) at the path point's orientation R.
Vec3 wallNormalIn(const Mat3& R, MillingMode mode) {
  if (mode == MillingMode::kSlot) return Vec3::Zero();
  return R * millToTool(mode == MillingMode::kUp ? Vec3::UnitY() : Vec3(-Vec3::UnitY()));
}

/// The command the controller's IK gives for the path point T_W_tcp (the link angles θ_d of the
/// real robot seed it): θ_d itself without a calibration (nominal = real).
Vec6 uncompensatedCommand(const PredictionModel& m, const Pose& T_W_tcp, const Vec6& theta_d) {
  if (!m.calibrated) return theta_d;
  const nc::Model& n = controllerModel(m);
  const IkNearResult ik =
      solveIkNear(m.ik, T_W_tcp * n.T_L6_tcp.inverse() * n.T_L6_flange, theta_d);
  return ik.converged ? ik.q : theta_d;
}

CuttingDecision decision(bool cutting, std::string reason,
                         std::optional<MillingEngagement> engagement = std::nullopt) {
  CuttingDecision c;
  c.cutting = cutting;
  c.reason = std::move(reason);
  c.engagement = engagement;
  return c;
}

/// The engagement tracker of a box stock; none without one.
std::optional<EngagementTracker> boxStockTracker(const MillingSpec& s) {
  if (!s.stock_box_min || !s.stock_box_max) return std::nullopt;
  StockShape stock;
  stock.top_z = s.stock_box_max->z();
  stock.box_min = s.stock_box_min;
  stock.box_max = s.stock_box_max;
  return EngagementTracker(stock, s.tool.diameter);
}

/// The decision of a non-rapid move a → b with a box stock (milling_engagement.hpp).
CuttingDecision engagedDecision(EngagementTracker& tracker, const std::optional<Vec3>& a,
                                const Vec3& b) {
  CuttingDecision c;
  if (!a) {
    c = decision(false, "first point of a feed chain: no move into it (box stock)", std::nullopt);
    return c;
  }
  const MillingEngagement e = tracker.cut(*a, b);
  if (!e.cuts()) {
    c = decision(false, "the move engages no material (box stock and the earlier passes)", e);
    return c;
  }
  c = decision(
      true,
      "engaged: ae " + mm(e.ae) + " mm, ap " + mm(e.ap) + " mm (box stock and the earlier passes)",
      e);
  return c;
}

}  // namespace

ForceFixedPoint solveForceFixedPoint(const std::function<bool(const Vec3&, Vec3&)>& phi,
                                     const Vec3& F0, ForceUpdate update, double tolerance,
                                     int max_evaluations, Mat3* jacobian) {
  ForceFixedPoint out;
  Vec3 F = F0;
  Vec3 image;
  ++out.evaluations;
  if (!phi(F, image)) {
    out.map_failed = true;
    return out;
  }
  Vec3 r = image - F;
  // Broyden's estimate of ∂r/∂F (Φ constant: −I)
  Mat3 J = jacobian != nullptr ? *jacobian : Mat3(-Mat3::Identity());
  const auto done = [&](bool converged) {
    out.converged = converged;
    if (jacobian != nullptr) *jacobian = J;
    return out;
  };
  while (true) {
    out.force = F + r;
    if (r.norm() <= tolerance) return done(true);
    if (out.evaluations >= max_evaluations) return done(false);
    Vec3 step = r;  // the plain step: F + r = Φ(F)
    if (update == ForceUpdate::kBroyden) {
      const Eigen::ColPivHouseholderQR<Mat3> qr(J);
      if (qr.rank() == 3) step = qr.solve(-r);
    }
    // a step whose Φ cannot be evaluated is halved (Broyden; the plain iteration stops)
    Vec3 F_next = F + step;
    Vec3 r_next;
    bool ok = false;
    for (int half = 0; half < 6 && out.evaluations < max_evaluations; ++half) {
      ++out.evaluations;
      ok = phi(F_next, image);
      if (ok || update == ForceUpdate::kPlain) break;
      step *= 0.5;
      F_next = F + step;
    }
    if (!ok) {
      out.map_failed = true;
      return done(false);
    }
    r_next = image - F_next;
    const Vec3 dF = F_next - F;
    if (update == ForceUpdate::kBroyden && dF.squaredNorm() > 0)
      J += ((r_next - r) - J * dF) * dF.transpose() / dF.squaredNorm();
    F = F_next;
    r = r_next;
  }
}

CuttingDecider::CuttingDecider(const MillingSpec& s, const Pose& T_W_wobj)
    : s_(s), T_wobj_W_(T_W_wobj.inverse()), tracker_(boxStockTracker(s)) {}

CuttingDecision CuttingDecider::operator()(const MillingPathPoint& p) {
  const MillingSpec& s = s_;
  const double vf = s.cut.fz * s.tool.teeth * s.cut.spindle_rpm / 60.0;  // m/s
  const double v_max = kRapidSpeedFactor * vf;
  CuttingDecision c;
  const Vec3 tip = (T_wobj_W_ * p.T_W_tcp).translation();
  const double z = tip.z();
  if (p.speed > v_max) {
    prev_tip_.reset();  // a rapid move removes nothing (and breaks the chain of moves)
    c = decision(false, "rapid: programmed " + fmt(p.speed * 1e3, 1) + " mm/s > " +
                            fmt(kRapidSpeedFactor, 2) + " x feed speed " + fmt(vf * 1e3, 1) +
                            " mm/s");
    c.rapid = true;
    return c;
  }
  if (tracker_) {
    c = engagedDecision(*tracker_, prev_tip_, tip);
    prev_tip_ = tip;
    return c;
  }
  if (s.stock_top_z) {
    const double depth = *s.stock_top_z - z;
    if (depth >= s.cut.ap - kDepthTolerance) {
      return decision(true, "feed move at depth " + mm(depth) + " mm below the stock top (ap " +
                                mm(s.cut.ap) + " mm)");
    }
    return decision(false, depth <= 0 ? "above the stock top by " + mm(-depth) + " mm"
                                      : "depth " + mm(depth) + " mm < ap " + mm(s.cut.ap) +
                                            " mm: not at the cutting depth");
  }
  if (!z_ref_) z_ref_ = z;
  if (std::abs(z - *z_ref_) <= kDepthTolerance)
    return decision(true, "feed move at the depth of the first feed move");
  return decision(false, "tool " + mm(z - *z_ref_) + " mm from the depth of the first feed move");
}

std::vector<CuttingDecision> decideCutting(const MillingSpec& s, const Pose& T_W_wobj,
                                           const std::vector<MillingPathPoint>& points) {
  CuttingDecider decide(s, T_W_wobj);
  std::vector<CuttingDecision> out(points.size());
  for (size_t i = 0; i < points.size(); ++i) out[i] = decide(points[i]);
  return out;
}

namespace {

/// The cut at a path point: the cell's, or the engagement's ae/ap (box stock), with its stability
/// cut and nominal force.
struct PointCut {
  MillingModel model;
  StabilityCut stability;
  Vec3 F_nom{Vec3::Zero()};
};
std::shared_ptr<const PointCut> pointCut(MillingModel model) {
  auto c = std::make_shared<PointCut>();
  c->stability = stabilityCutOf(model);
  c->F_nom = millingMeanForce(model, model.cut.fz, model.cut.ae);
  c->model = std::move(model);
  return c;
}

/// A path's points (or cutting decisions) by path index: a whole vector, or — a path read block
/// by block — the two blocks the pipeline holds (block k of `block` elements in slot k % 2: the
/// first chain's block and the block before it, which the second chain reads). size(): the
/// vector's, or (block by block) every index asked for is held.
template <class T>
class PathWindow {
 public:
  explicit PathWindow(const std::vector<T>& whole) : whole_(&whole) {}
  explicit PathWindow(size_t block) : block_(block) {}
  const T& operator[](size_t i) const {
    return whole_ != nullptr ? (*whole_)[i] : slots_[(i / block_) % 2][i % block_];
  }
  [[nodiscard]] size_t size() const {
    return whole_ != nullptr ? whole_->size() : std::numeric_limits<size_t>::max();
  }
  /// The slot of block k (block by block), to be filled.
  std::vector<T>& slot(size_t k) { return slots_[k % 2]; }

 private:
  const std::vector<T>* whole_{nullptr};
  size_t block_{1};
  std::array<std::vector<T>, 2> slots_;
};

/// What both chains of the path read.
struct PathSetup {
  const PredictionModel& m;
  const PathWindow<Pose>& points;
  const PathWindow<CuttingDecision>* cutting;
  Mat3 C_tool;
  CouplingOptions copt;
  MillingPathOptions options;
};

/// The coupling options at point i: the tooth passes since the previous point from the program's
/// spacing (|p_i − p_{i−1}| / fz rounded, at least 1) unless the cell gives them or i = 0.
CouplingOptions pointCoupling(const PathSetup& s, size_t i, bool& from_cell) {
  const MillingSpec& spec = s.m.process.milling;
  from_cell = spec.teeth_between_points_given || i == 0;
  if (from_cell) return s.copt;
  CouplingOptions o = s.copt;
  const double spacing = (s.points[i].translation() - s.points[i - 1].translation()).norm();
  const double teeth = std::round(spacing / spec.cut.fz);
  o.teeth_between_points = teeth < 1 ? 1 : teeth > 1e6 ? 1000000 : static_cast<int>(teeth);
  return o;
}

/// The engagement along one chain's real tool path (box stock; milling_engagement.hpp): the move
/// into a point is queried at one tool position and recorded at another (where the tool really
/// went), both base frame; a rapid point breaks the chain of moves. Without a box stock (or
/// without cutting decisions) nothing is tracked.
class RealPathEngagement {
 public:
  explicit RealPathEngagement(const PathSetup& s)
      : tracker_(s.cutting != nullptr ? boxStockTracker(s.m.process.milling) : std::nullopt),
        T_stock_W_(s.options.T_W_stock.inverse()) {}
  [[nodiscard]] bool tracked() const { return tracker_.has_value(); }
  /// The engagement of the move into a point whose tool is at `tip_W`; none for a rapid point or
  /// the first point of a chain of moves.
  std::optional<MillingEngagement> query(bool rapid, const Vec3& tip_W) {
    if (rapid) {
      from_query_.reset();
      return std::nullopt;
    }
    const Vec3 b = T_stock_W_ * tip_W;
    std::optional<MillingEngagement> e;
    if (from_query_) e = tracker_->engagementAt(*from_query_, b);
    from_query_ = b;
    return e;
  }
  /// Records the move into the point, the tool really at `real_W`.
  void record(bool rapid, const Vec3& real_W) {
    if (rapid) {
      from_real_.reset();
      return;
    }
    const Vec3 b = T_stock_W_ * real_W;
    if (from_real_) tracker_->record(*from_real_, b);
    from_real_ = b;
  }

 private:
  std::optional<EngagementTracker> tracker_;
  Pose T_stock_W_;
  std::optional<Vec3> from_query_, from_real_;
};

bool sameEngagement(const MillingCut& cut, const MillingEngagement& e) {
  return cut.ae == e.ae && cut.ap == e.ap;
}

std::string engagementText(const MillingEngagement& e) {
  return "ae " + mm(e.ae) + " mm, ap " + mm(e.ap) + " mm";
}

nc::Loads loadsWith(const PredictionModel& m, const Vec3& F_mill) {
  nc::Loads l;
  l.gravity = m.gravity;
  l.tcp_tool.force = millToTool(F_mill);
  return l;
}

/// The spindle/tool's own deflection under F, base frame (it adds to the robot's).
Vec3 toolBending(const PathSetup& s, size_t i, const Vec3& F_mill) {
  return s.points[i].linear() * millToTool(s.C_tool * F_mill);
}

/// The robot's compliance at θ_d (milling frame) linearised at the cut's nominal force F_nom, in
/// series with the spindle/tool's (milling_robot.hpp lineariseCompliance): the uncompensated
/// coupling evaluates it, and its C is the compensated chain's compliance at the point.
LinearCompliance pointCompliance(const PathSetup& s, const Vec6& theta_d, const Vec3& F_nom) {
  const PredictionModel& m = s.m;
  LinearCompliance l =
      lineariseCompliance(robotMillingCompliance(m.model, m.compliance, theta_d, m.gravity), F_nom);
  l.delta_ref += s.C_tool * F_nom;
  l.C += s.C_tool;
  return l;
}

/// A chain's mean-force memo (milling.hpp MeanForceMemo) for the cut it couples with, reset when
/// the cut changes (the memo holds the cut, so its address is not reused meanwhile).
class CutMemo {
 public:
  MeanForceMemo& operator()(const std::shared_ptr<const PointCut>& cut) {
    if (cut != cut_) {
      memo_.reset();
      cut_ = cut;
    }
    return memo_;
  }

 private:
  std::shared_ptr<const PointCut> cut_;
  MeanForceMemo memo_;
};

/// A resolved revolution to compute (edgeRevolution at the cut, with the modes) and its result;
/// the points that reuse it share it.
struct EdgeJob {
  std::shared_ptr<const PointCut> cut;
  ModalModel dyn;  ///< empty: the rigid tool at the programmed cut
  double fz{0}, ae{0}, ap{0};
  EdgeRevolution result;
};
using EdgeRef = std::shared_ptr<EdgeJob>;

/// The last revolution along the path and the cut and modes it was computed with.
struct EdgeCache {
  ModalModel modes;
  double fz{0}, ae{0}, ap{0};
  EdgeRef nominal, corrected;
};

/// The first chain along the path, in path order: the cutting decision's engagement, the IK with
/// continuity, the uncompensated coupled solve and deviation, the modes, the chatter check and
/// which revolution a point resolves (computed later, on the workers).
class UncompensatedChain {
 public:
  UncompensatedChain(const PathSetup& s, const Vec6* seed)
      : s_(s),
        cell_(pointCut(millingModelOf(s.m.process.milling))),
        cut_(cell_),
        d_(s.m),
        engagement_(s) {
    if (seed != nullptr) prev_ = *seed;
  }
  /// Point i into `p`; false when it has no admissible IK (p.reason says why). `cut` receives
  /// the point's cut, `compliance` its linearised C (pointCompliance; cutting points), `edges`
  /// the revolutions it reports (nominal, corrected) when cutting.
  bool run(size_t i, PathPointCompensation& p, std::shared_ptr<const PointCut>& cut,
           Mat3& compliance, std::pair<EdgeRef, EdgeRef>& edges, std::vector<EdgeRef>& jobs);

 private:
  bool inverseKinematics(size_t i, PathPointCompensation& p);
  std::optional<Vec3> engageRealPath(size_t i, const CuttingDecision& cd, const Vec6& q_before,
                                     PathPointCompensation& p);
  void useEngagement(const MillingEngagement& e);
  Vec3 deviationUnder(size_t i, const Vec6& q_before, const Vec3& F);
  void reuseOrQueueEdges(const ModalModel& dyn, const CouplingResult& c,
                         std::pair<EdgeRef, EdgeRef>& edges, std::vector<EdgeRef>& jobs);
  const PathSetup& s_;
  std::shared_ptr<const PointCut> cell_, cut_;
  PredictionData d_;
  std::optional<Vec6> prev_;
  CouplingState state_;  // the uncompensated path's memory (for the "before" deviation)
  /// G at the previous point's converged solve with the current cut: the warm start of the
  /// next solve (from the previous δ); none after a point that did not cut, did not converge or
  /// used another cut
  std::optional<Mat3> warm_gain_;
  StabilityCache stability_cache_;
  ModeCouplingCache mode_coupling_cache_;
  EdgeCache edge_cache_;
  CutMemo memo_;
  RealPathEngagement engagement_;
};

bool UncompensatedChain::inverseKinematics(size_t i, PathPointCompensation& p) {
  const PredictionModel& m = s_.m;
  // IK of the real robot with continuity (realIk: FK_real(θ_d) = the path point)
  const Pose T_flange = s_.points[i] * m.model.T_L6_tcp.inverse() * m.model.T_L6_flange;
  const Vec6 start = prev_ ? *prev_ : m.reference_pose;
  IkOptions opt;
  opt.seed = &start;
  solveIk(realIk(m), T_flange, opt, d_.ik);
  double best = 1e300;
  bool found = false;
  for (int k = 0; k < d_.ik.count; ++k) {
    const IkSolution& sol = d_.ik.solutions[static_cast<size_t>(k)];
    if (!sol.converged || !sol.within_limits || sol.singular_wrist || sol.singular_shoulder)
      continue;
    const double dist = (sol.q - start).squaredNorm();
    if (dist < best) {
      best = dist;
      p.theta_d = sol.q;
      found = true;
    }
  }
  if (!found) {
    p.reason = d_.ik.count == 0 ? describeIkFailure(d_.ik)
                                : "no admissible IK solution (limits, singularity)";
    return false;
  }
  prev_ = p.theta_d;
  return true;
}

void UncompensatedChain::reuseOrQueueEdges(const ModalModel& dyn, const CouplingResult& c,
                                           std::pair<EdgeRef, EdgeRef>& edges,
                                           std::vector<EdgeRef>& jobs) {
  EdgeCache& cache = edge_cache_;
  const bool same = cache.corrected && sameModes(dyn, cache.modes) &&
                    std::abs(c.fz_effective - cache.fz) <= kEdgeReuseTolerance &&
                    std::abs(c.ae_effective - cache.ae) <= kEdgeReuseTolerance &&
                    std::abs(c.ap_effective - cache.ap) <= kEdgeReuseTolerance;
  if (!same) {
    const MillingCut& cut = cut_->model.cut;
    if (!cache.corrected) {
      cache.nominal =
          std::make_shared<EdgeJob>(EdgeJob{cut_, ModalModel{}, cut.fz, cut.ae, cut.ap, {}});
      jobs.push_back(cache.nominal);
    }
    cache.corrected = std::make_shared<EdgeJob>(
        EdgeJob{cut_, dyn, c.fz_effective, c.ae_effective, c.ap_effective, {}});
    jobs.push_back(cache.corrected);
    cache.modes = dyn;
    cache.fz = c.fz_effective;
    cache.ae = c.ae_effective;
    cache.ap = c.ap_effective;
  }
  edges = {cache.nominal, cache.corrected};
}

/// The point's cut with the engagement e (rebuilt, and the caches dropped, when it changes).
void UncompensatedChain::useEngagement(const MillingEngagement& e) {
  if (sameEngagement(cut_->model.cut, e)) return;
  cut_ = pointCut(engagedModel(cell_->model, e));
  warm_gain_.reset();
  stability_cache_.valid = false;
  mode_coupling_cache_.valid = false;
  edge_cache_ = EdgeCache{};
}

/// The uncompensated tool's deviation from path point i under the milling force F (base frame):
/// the controller's command q_before under gravity and F, and the tool's bending.
Vec3 UncompensatedChain::deviationUnder(size_t i, const Vec6& q_before, const Vec3& F) {
  const PredictionModel& m = s_.m;
  nc::Deflection db = nc::predictDeflection(m.model, d_.nc, m.compliance, q_before, loadsWith(m, F),
                                            {}, controllerOffset(m, d_.nc, q_before));
  if (m.calibrated) nc::referToControllerPose(db, controllerTcp(m, q_before));
  return db.dp + toolBending(s_, i, F);
}

/// Box stock: the engagement of the move into point i on the uncompensated real path — queried
/// where the tool is without the milling force (the coupling adds the cut's own deflection) — and
/// whether the point cuts there. Returns that force-free deviation (none for a rapid point).
std::optional<Vec3> UncompensatedChain::engageRealPath(size_t i, const CuttingDecision& cd,
                                                       const Vec6& q_before,
                                                       PathPointCompensation& p) {
  std::optional<Vec3> free;
  if (!cd.rapid) free = deviationUnder(i, q_before, Vec3::Zero());
  const std::optional<MillingEngagement> e =
      engagement_.query(cd.rapid, s_.points[i].translation() + (free ? *free : Vec3::Zero()));
  const bool cuts = !cd.rapid && e && e->cuts();
  if (cuts != p.cutting) {
    p.cutting = cuts;
    p.cutting_reason =
        cuts ? "engaged on the real path: " + engagementText(*e) +
                   " (the programmed path engages none: the earlier passes left material where "
                   "the tool really went)"
             : std::string(
                   "the real path engages no material (the programmed path does: the "
                   "earlier passes removed it where the tool really went)");
  }
  if (cuts) useEngagement(*e);
  return free;
}

bool UncompensatedChain::run(size_t i, PathPointCompensation& p,
                             std::shared_ptr<const PointCut>& cut, Mat3& compliance,
                             std::pair<EdgeRef, EdgeRef>& edges, std::vector<EdgeRef>& jobs) {
  const PredictionModel& m = s_.m;
  const CuttingDecision* cd =
      s_.cutting != nullptr && i < s_.cutting->size() ? &(*s_.cutting)[i] : nullptr;
  if (cd != nullptr) {
    p.cutting = cd->cutting;
    p.cutting_reason = cd->reason;
    if (cd->cutting && cd->engagement && !engagement_.tracked()) useEngagement(*cd->engagement);
  }
  const bool rapid = cd != nullptr && cd->rapid;
  if (!inverseKinematics(i, p)) {
    // where the tool really goes is unknown: the programmed point
    if (engagement_.tracked()) {
      engagement_.query(rapid, s_.points[i].translation());
      engagement_.record(rapid, s_.points[i].translation());
    }
    return false;
  }
  // the uncompensated command: the controller's IK of the path point (θ_d without a
  // calibration)
  const Vec6 q_before = uncompensatedCommand(m, s_.points[i], p.theta_d);
  std::optional<Vec3> free;  // the deviation without the milling force (box stock)
  if (engagement_.tracked()) free = engageRealPath(i, *cd, q_before, p);
  if (free) p.deviation_free = *free;
  cut = cut_;
  p.ae = cut_->model.cut.ae;
  p.ap = cut_->model.cut.ap;
  // uncompensated: the robot at θ_d under the coupled force
  Vec3 F_before = Vec3::Zero();
  CouplingOptions copt = pointCoupling(s_, i, p.teeth_from_cell);
  p.teeth_between_points = copt.teeth_between_points;
  if (p.cutting) {
    const LinearCompliance lc = pointCompliance(s_, p.theta_d, cut_->F_nom);
    compliance = lc.C;
    if (warm_gain_) {
      copt.start = state_.delta_prev;
      copt.start_gain = warm_gain_;
    }
    const CouplingResult cb = coupleMillingPoint(
        cut_->model, [&lc](const Vec3& G) { return lc(G); }, state_, copt, &memo_(cut_));
    state_ = cb.next;
    warm_gain_ = cb.converged ? cb.gain : std::nullopt;
    p.before_fz_effective = cb.fz_effective;
    F_before = cb.force;
    p.before_status = couplingStatusName(cb.status);
    p.before_iterations = cb.iterations;
    p.before_residual = cb.residual;
    p.before_loop_gain = cb.loop_gain;
    p.before_force = cb.force;
    if (const std::optional<ModalModel> dyn = pointModes(m, p)) {
      checkStability(*dyn, cut_->stability, m.process.milling.cut.spindle_rpm, stability_cache_, p);
      checkModeCoupling(cut_->model, *dyn, mode_coupling_cache_, p);
      if (s_.options.resolve_edges) reuseOrQueueEdges(*dyn, cb, edges, jobs);
    }
  } else {
    state_ = CouplingState{};  // the tool left the material
    warm_gain_.reset();
    p.before_status = "not_cutting";
  }
  // its deviation from the path point under the coupled force: where the tool really goes
  p.deviation_before = free && !p.cutting ? *free : deviationUnder(i, q_before, F_before);
  if (engagement_.tracked())
    engagement_.record(rapid, s_.points[i].translation() + p.deviation_before);
  if (p.cutting)
    p.surface_error_before =
        p.deviation_before.dot(wallNormalIn(s_.points[i].linear(), cut_->model.cut.mode));
  return true;
}

/// A point's resolved revolution (nominal, corrected) into `p`.
void reportEdges(const std::pair<EdgeRef, EdgeRef>& edges, PathPointCompensation& p) {
  if (!edges.second) return;
  const EdgeRevolution& r = edges.second->result;
  p.edges_checked = true;
  p.edges_converged = r.converged;
  p.tooth_feed = r.tooth_feed;
  p.peak_xy_nominal = edges.first->result.peak_xy;
  p.peak_xy = r.peak_xy;
  Vec3 lo = Vec3::Constant(1e300);
  Vec3 hi = Vec3::Constant(-1e300);
  for (const Vec3& x : r.vibration) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  p.vibration_pp = r.vibration.empty() ? Vec3::Zero() : Vec3(hi - lo);
}

/// The second chain along the path, in path order: the compensated command of each point whose
/// IK the first chain found (its coupling memory and, with a box stock, its engagement are the
/// compensated path's).
class CompensatedChain {
 public:
  explicit CompensatedChain(const PathSetup& s)
      : s_(s), cell_(millingModelOf(s.m.process.milling)), d_(s.m), engagement_(s) {}
  /// `cut`: the first chain's cut at the point; `C`: the point's linearised compliance (robot and
  /// tool, milling frame; pointCompliance), zero where the first chain does not cut.
  void run(size_t i, const std::shared_ptr<const PointCut>& cut, const Mat3& C,
           PathPointCompensation& p);
  /// A point the first chain found no IK for: the compensated tool is taken to pass the
  /// programmed point.
  void skip(size_t i);

 private:
  ComplianceFunction residualCompliance(size_t i, const Vec6& theta_cmd, const Vec3& F,
                                        const Mat3& C);
  Vec6 commandFor(size_t i, const PathPointCompensation& p,
                  const Eigen::ColPivHouseholderQR<Mat6>& J, const Vec3& G);
  std::shared_ptr<const PointCut> engage(size_t i, const std::shared_ptr<const PointCut>& cut,
                                         PathPointCompensation& p);
  void compensate(size_t i, const std::shared_ptr<const PointCut>& cut_ref, const Mat3& C,
                  PathPointCompensation& p);
  [[nodiscard]] bool rapid(size_t i) const {
    return s_.cutting != nullptr && i < s_.cutting->size() && (*s_.cutting)[i].rapid;
  }
  const PathSetup& s_;
  MillingModel cell_;
  PredictionData d_;
  CouplingState state_;
  CutMemo memo_;
  RealPathEngagement engagement_;
  std::shared_ptr<const PointCut> own_;  ///< the cut of its own engagement when it differs
  /// Broyden's estimate of ∂(Φ(F) − F)/∂F, carried from point to point
  Mat3 force_jacobian_{-Mat3::Identity()};
  /// The previous point's converged force and its cut: the start of the next point's force
  /// fixed point with the same cut (none after a point that did not cut or did not converge)
  std::optional<Vec3> last_force_;
  std::shared_ptr<const PointCut> last_cut_;
};

/// Box stock: the compensated path's engagement of the move into point i (queried at the path
/// point: the coupling's δ is the whole deviation from it) decides whether the compensated tool
/// cuts and with which cut — the first chain's when the engagement is the same, else its own.
std::shared_ptr<const PointCut> CompensatedChain::engage(size_t i,
                                                         const std::shared_ptr<const PointCut>& cut,
                                                         PathPointCompensation& p) {
  p.cutting_after = p.cutting;
  if (!engagement_.tracked()) {
    p.ae_after = p.ae;
    p.ap_after = p.ap;
    return cut;
  }
  const std::optional<MillingEngagement> e =
      engagement_.query(rapid(i), s_.points[i].translation());
  p.cutting_after = !rapid(i) && e && e->cuts();
  if (!p.cutting_after) return cut;
  p.ae_after = e->ae;
  p.ap_after = e->ap;
  if (sameEngagement(cut->model.cut, *e)) return cut;
  if (!own_ || !sameEngagement(own_->model.cut, *e)) own_ = pointCut(engagedModel(cell_, *e));
  return own_;
}

void CompensatedChain::skip(size_t i) {
  if (!engagement_.tracked()) return;
  engagement_.query(rapid(i), s_.points[i].translation());
  engagement_.record(rapid(i), s_.points[i].translation());
}

void CompensatedChain::run(size_t i, const std::shared_ptr<const PointCut>& cut, const Mat3& C,
                           PathPointCompensation& p) {
  compensate(i, engage(i, cut, p), C, p);
  if (engagement_.tracked()) {
    const Vec3 real = s_.points[i].translation() + (p.ok ? p.residual : Vec3::Zero());
    engagement_.record(rapid(i), real);
  }
}

/// The controller command that puts the link side at θ_d under force G (exact inverse; a
/// gravity-compensating controller adds its own offset: θ_cmd + off(θ_cmd) = θ_m), with the link
/// side pre-offset for the tool's bending: θ_d + J⁻¹ [−bending; 0].
Vec6 CompensatedChain::commandFor(size_t i, const PathPointCompensation& p,
                                  const Eigen::ColPivHouseholderQR<Mat6>& J, const Vec3& G) {
  const PredictionModel& m = s_.m;
  Vec6 target = p.theta_d;
  if (!G.isZero() && J.rank() == 6) {
    Vec6 twist = Vec6::Zero();
    twist.head<3>() = -toolBending(s_, i, G);
    target = p.theta_d + J.solve(twist);
  }
  const Vec6 theta_m = nc::compensateCommand(m.model, d_.nc, m.compliance, target, loadsWith(m, G));
  Vec6 cmd = theta_m;
  for (int it = 0; it < 20 && m.controller.kind != nc::ControllerReference::Kind::kNone; ++it)
    cmd = theta_m - controllerOffset(m, d_.nc, cmd);
  return cmd;
}

/// The compensated robot's deviation from the nominal tool position under a force G (milling
/// frame) at the command θ_cmd: the full equilibrium at the current force F, and the point's
/// linearised compliance C for G − F: δ(G) ≈ δ(F) + C (G − F). Throws (the coupling's
/// "compliance_failed") when that equilibrium does not converge.
ComplianceFunction CompensatedChain::residualCompliance(size_t i, const Vec6& theta_cmd,
                                                        const Vec3& F, const Mat3& C) {
  const PredictionModel& m = s_.m;
  const Pose& T = s_.points[i];
  const nc::Deflection dg =
      nc::predictDeflection(m.model, d_.nc, m.compliance, theta_cmd, loadsWith(m, F), {},
                            controllerOffset(m, d_.nc, theta_cmd));
  if (!dg.converged) {
    return [](const Vec3&) -> Vec3 {
      throw std::runtime_error("the compliance equilibrium did not converge");
    };
  }
  LinearCompliance l;
  l.F_ref = F;
  l.delta_ref = millToTool(T.linear().transpose() * (dg.T_real.translation() - T.translation())) +
                s_.C_tool * F;
  l.C = C;
  return [l](const Vec3& G) { return l(G); };
}

void CompensatedChain::compensate(size_t i, const std::shared_ptr<const PointCut>& cut_ref,
                                  const Mat3& C_first, PathPointCompensation& p) {
  const PredictionModel& m = s_.m;
  const PointCut& cut = *cut_ref;
  MeanForceMemo& memo = memo_(cut_ref);
  const Pose& T = s_.points[i];
  const Mat3 R = T.linear();
  const bool cutting = p.cutting_after;
  // the first chain's compliance, or the point's own where only the compensated tool cuts
  const Mat3 C =
      cutting && C_first.isZero() ? pointCompliance(s_, p.theta_d, cut.F_nom).C : C_first;
  // the first chain's tooth passes since the previous point (pointCoupling)
  CouplingOptions copt = s_.copt;
  copt.teeth_between_points = static_cast<int>(p.teeth_between_points);
  copt.loop_gain = false;  // the loop gain only of the last solve (it is what is reported)
  nc::forwardKinematics(m.model, d_.nc, p.theta_d);
  const Eigen::ColPivHouseholderQR<Mat6> J_qr(nc::tcpJacobian(m.model, d_.nc));
  // force fixed point with the exact inverse (no force at a point that does not cut):
  // Φ(F) = the coupled force with the command compensated for F
  CouplingResult ca;
  ca.converged = true;
  ca.status = CouplingStatus::kConverged;
  ComplianceFunction compliance;
  const auto phi = [&](const Vec3& F, Vec3& out) {
    p.theta_cmd = commandFor(i, p, J_qr, F);
    compliance = residualCompliance(i, p.theta_cmd, F, C);
    ca = coupleMillingPoint(cut.model, compliance, state_, copt, &memo);
    out = ca.force;
    return ca.converged;
  };
  Vec3 F = Vec3::Zero();
  bool conv = !cutting;
  p.force_iterations = 0;
  if (cutting) {
    const Vec3 F0 = last_force_ && last_cut_ == cut_ref ? *last_force_ : cut.F_nom;
    const ForceFixedPoint fp =
        solveForceFixedPoint(phi, F0, s_.options.force_update, 1e-9, 20, &force_jacobian_);
    F = fp.force;
    conv = fp.converged;
    p.force_iterations = fp.evaluations;
  }
  p.coupling_converged = ca.converged;
  p.coupling_iterations = ca.iterations;
  p.coupling_status = cutting ? couplingStatusName(ca.status) : "not_cutting";
  p.coupling_residual = ca.residual;
  if (cutting) p.loop_gain = couplingLoopGain(cut.model, compliance, state_, copt, ca, &memo);
  p.force = F;
  last_force_.reset();  // set again when the point converges
  if (!conv) {
    p.reason = ca.converged ? "the force fixed point did not converge"
                            : std::string("the coupled milling iteration did not converge (") +
                                  couplingStatusName(ca.status) + ")";
    return;
  }
  state_ = cutting ? ca.next : CouplingState{};
  last_force_ = cutting ? std::optional<Vec3>(F) : std::nullopt;
  last_cut_ = cut_ref;
  p.theta_cmd = commandFor(i, p, J_qr, F);
  if (!withinLimits(m.ik, p.theta_cmd)) {
    p.reason = "the compensated command leaves the joint limits";
    return;
  }
  nc::forwardKinematics(controllerModel(m), d_.nc, p.theta_cmd);  // FK_nom: what is programmed
  p.T_programmed = d_.nc.T_W_tcp;
  const nc::Deflection da =
      nc::predictDeflection(m.model, d_.nc, m.compliance, p.theta_cmd, loadsWith(m, F), {},
                            controllerOffset(m, d_.nc, p.theta_cmd));
  p.residual = da.T_real.translation() + toolBending(s_, i, F) - T.translation();
  if (cutting) p.surface_error = p.residual.dot(wallNormalIn(R, cut.model.cut.mode));
  p.config_text = formatConfig(configurationOf(m.ik, m.robot.card, p.theta_cmd, m.config_options));
  p.ok = da.converged;
  if (!p.ok) p.reason = "the compliance equilibrium did not converge at the compensated command";
}

/// One block [b, e) of the path after the first chain: its results (the first chain's part),
/// the points it found an IK for, their cuts, tooth passes and revolutions.
struct PathBlock {
  size_t b{0}, e{0};
  std::vector<PathPointCompensation> out;  ///< point b + k at k
  std::vector<char> found;
  std::vector<std::shared_ptr<const PointCut>> cut;
  std::vector<Mat3> compliance;  ///< linearised, per point (cutting points)
  std::vector<std::pair<EdgeRef, EdgeRef>> edges;
  std::vector<EdgeRef> jobs;  ///< the revolutions first needed in this block
};

void runFirstChain(UncompensatedChain& chain, PathBlock& blk) {
  const size_t n = blk.e - blk.b;
  blk.out.assign(n, PathPointCompensation{});
  blk.found.assign(n, 0);
  blk.cut.assign(n, nullptr);
  blk.compliance.assign(n, Mat3::Zero());
  blk.edges.assign(n, {});
  blk.jobs.clear();
  for (size_t k = 0; k < n; ++k) {
    blk.found[k] =
        chain.run(blk.b + k, blk.out[k], blk.cut[k], blk.compliance[k], blk.edges[k], blk.jobs) ? 1
                                                                                                : 0;
  }
}

void resolveBlockEdges(PathBlock& blk, int threads) {
  parallelFor(blk.jobs.size(), threads, [&](int, size_t k) {
    EdgeJob& j = *blk.jobs[k];
    j.result = edgeRevolution(j.cut->model, j.dyn, j.fz, j.ae, j.ap);
  });
  for (size_t k = 0; k < blk.edges.size(); ++k) reportEdges(blk.edges[k], blk.out[k]);
}

void runSecondChain(CompensatedChain& chain, PathBlock& blk) {
  for (size_t k = 0; k < blk.e - blk.b; ++k) {
    if (blk.found[k]) {
      chain.run(blk.b + k, blk.cut[k], blk.compliance[k], blk.out[k]);
    } else {
      chain.skip(blk.b + k);
    }
  }
  // the block's revolutions and cuts are not needed any more (the chains keep their own)
  blk.edges.clear();
  blk.jobs.clear();
  blk.cut.clear();
}

/// The two chains over the path as a pipeline: `fill(k, b)` makes block k (its first point b)
/// readable through the setup's windows and returns its end (b: the path ended).
void runPipeline(const PathSetup& setup, const Vec6* seed, const MillingPathSink& sink,
                 const std::function<size_t(size_t, size_t)>& fill) {
  const PredictionModel& m = setup.m;
  if (!m.has_process || m.process.type != ProcessType::kMilling) {
    throw std::invalid_argument("compensateMillingPath needs a milling process");
  }
  const MillingPathOptions& options = setup.options;
  const int threads = std::max(1, options.threads);
  UncompensatedChain first(setup, seed);
  CompensatedChain second(setup);
  // pipeline: the first chain over block k (and its revolutions) while the second chain runs
  // over block k − 1 on a task of its own (inline with one thread); block k − 1 goes to the sink
  // while the second chain runs over block k
  PathBlock blocks[2];
  std::future<void> pending;
  PathBlock* done = nullptr;  // the block whose second chain ran, not yet handed to the sink
  const auto hand = [&sink](PathBlock& blk) {
    sink(blk.b, std::span<PathPointCompensation>(blk.out));
    blk.out.clear();
  };
  for (size_t b = 0, k = 0;; ++k) {
    const size_t e = fill(k, b);
    if (e <= b) break;
    PathBlock& blk = blocks[k % 2];
    blk.b = b;
    blk.e = e;
    b = e;
    runFirstChain(first, blk);
    // the revolutions on all the workers (each writes only its own job), beside the second
    // chain's task over the block before: they are most of a resolved block's work
    resolveBlockEdges(blk, threads);
    if (pending.valid()) pending.get();
    if (threads > 1) {
      pending = std::async(std::launch::async, [&second, &blk] { runSecondChain(second, blk); });
    } else {
      runSecondChain(second, blk);
    }
    if (done != nullptr) hand(*done);
    done = &blk;
  }
  if (pending.valid()) pending.get();
  if (done != nullptr) hand(*done);
}

}  // namespace

void compensateMillingPath(const PredictionModel& m, const std::vector<Pose>& points,
                           const std::vector<CuttingDecision>* cutting, const Vec6* seed,
                           const MillingPathOptions& options, const MillingPathSink& sink) {
  const PathWindow<Pose> path(points);
  std::optional<PathWindow<CuttingDecision>> cuts;
  if (cutting != nullptr) cuts.emplace(*cutting);
  const PathSetup setup{m,
                        path,
                        cuts ? &*cuts : nullptr,
                        toolStaticCompliance(m.process.milling.tool_mode),
                        m.process.milling.coupling,
                        options};
  const size_t block = std::max<size_t>(1, options.block);
  runPipeline(setup, seed, sink,
              [&](size_t, size_t b) { return std::min(points.size(), b + block); });
}

void compensateMillingPath(const PredictionModel& m, const MillingPathSource& source,
                           bool with_cutting, const Vec6* seed, const MillingPathOptions& options,
                           const MillingPathSink& sink) {
  const size_t block = std::max<size_t>(1, options.block);
  PathWindow<Pose> path(block);
  PathWindow<CuttingDecision> cuts(block);
  const PathSetup setup{m,
                        path,
                        with_cutting ? &cuts : nullptr,
                        toolStaticCompliance(m.process.milling.tool_mode),
                        m.process.milling.coupling,
                        options};
  bool ended = false;
  runPipeline(setup, seed, sink, [&](size_t k, size_t b) {
    if (ended) return b;
    // slot k % 2 held block k − 2: both chains and the sink are done with it
    std::vector<Pose>& points = path.slot(k);
    std::vector<CuttingDecision>& cutting = cuts.slot(k);
    points.clear();
    cutting.clear();
    const size_t n = source(block, points, cutting);
    if (n > block || points.size() != n || (with_cutting && cutting.size() != n))
      throw std::logic_error("compensateMillingPath: the source gave a block of the wrong size");
    ended = n < block;
    return b + n;
  });
}

std::vector<PathPointCompensation> compensateMillingPath(
    const PredictionModel& m, const std::vector<Pose>& points,
    const std::vector<CuttingDecision>* cutting, const Vec6* seed,
    const MillingPathOptions& options) {
  std::vector<PathPointCompensation> out(points.size());
  compensateMillingPath(m, points, cutting, seed, options,
                        [&out](size_t first, std::span<PathPointCompensation> block) {
                          std::move(block.begin(), block.end(),
                                    out.begin() + static_cast<std::ptrdiff_t>(first));
                        });
  return out;
}

}  // namespace roprec
