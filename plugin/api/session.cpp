/// Session: a cell loaded once, targets filtered and joints predicted one at a time
/// (plugin/api/job.hpp).
#include <utility>

#include "plugin/api/job.hpp"

namespace roprec::api {

struct Session::Impl {
  PredictionContext context;
  CompensationOptions keep;  ///< orientation kept, positions compensated
};

Session::Session(const std::string& cell_path) : impl_(new Impl) {
  try {
    impl_->context = loadPredictionContext(cell_path, "", std::nullopt, "", 0.5, false);
  } catch (...) {
    delete impl_;
    throw;
  }
}

Session::~Session() { delete impl_; }

const PredictionContext& Session::context() const { return impl_->context; }

Session::Filtered Session::filterTarget(const Pose& T_W_wanted, const Vec6* seed_controller) {
  const PredictionModel& m = impl_->context.model;
  HoleRequest req;
  req.id = "target";
  req.T_W_tcp = T_W_wanted;
  if (seed_controller) req.ik_seed = fromControllerJoints(m.robot.card, *seed_controller);
  const std::vector<HoleCompensation> comp = compensateHoles(m, {req}, impl_->keep);
  const HoleCompensation& h = comp.front();
  Filtered f;
  f.before = h.before;
  if (!h.ok) {
    f.reason = h.reason;
    return f;
  }
  f.ok = true;
  f.T_programmed = h.T_programmed;
  f.joints_controller = toControllerJoints(m.robot.card, h.theta_cmd);
  f.config = h.config_text;
  f.residual = h.residual.norm();
  return f;
}

Session::JointPrediction Session::predictJoints(const Vec6& joints_controller) {
  const PredictionModel& m = impl_->context.model;
  JointPrediction p;
  const Vec6 q = fromControllerJoints(m.robot.card, joints_controller);
  // the pose the controller means by these joints (FK_nom; the real one without a calibration)
  nc::Data d(m.model);
  const nc::PositionResult pr = nc::forwardKinematics(controllerModel(m), d, q);
  if (!pr.converged) {
    p.reason = "the position problem did not converge at these joints";
    return p;
  }
  HoleRequest req;
  req.id = "joints";
  req.T_W_tcp = d.T_W_tcp;
  req.ik_seed = q;  // the commanded joints select their own IK solution
  PredictionData data(m);
  p.prediction = predictHole(m, data, req, &q);
  if (p.prediction.status != HoleStatus::kOk) {
    p.reason = p.prediction.reason;
    return p;
  }
  if ((p.prediction.joints - q).lpNorm<Eigen::Infinity>() > 1e-6) {
    p.reason =
        "these joints are not an admissible solution (joint limits or a singular wrist/shoulder)";
    return p;
  }
  p.ok = true;
  p.d_translation = p.prediction.d_robot;
  p.d_rotation = p.prediction.d_rot;
  p.U_work = p.prediction.U_work_exact;
  return p;
}

}  // namespace roprec::api
