#include "compensator/process/milling_robot.hpp"

#include <memory>
#include <stdexcept>

namespace roprec {

namespace {
struct State {
  nc::Model model;
  nc::JointCompliance c;
  nc::Vec6 theta_m;
  bool gravity{true};
  nc::Data data;
  Vec3 p0{Vec3::Zero()};
  Mat3 R_W_tcp{Mat3::Identity()};
  State(const nc::Model& m, const nc::JointCompliance& cc, const nc::Vec6& q, bool g)
      : model(m), c(cc), theta_m(q), gravity(g), data(model) {}
};
}  // namespace

ComplianceFunction robotMillingCompliance(const nc::Model& model, const nc::JointCompliance& c,
                                          const nc::Vec6& theta_m, bool gravity) {
  auto s = std::make_shared<State>(model, c, theta_m, gravity);
  nc::Loads none;
  none.gravity = gravity;
  const nc::Deflection d0 = nc::predictDeflection(s->model, s->data, s->c, theta_m, none);
  if (!d0.converged)
    throw std::runtime_error(
        "robot compliance: the equilibrium without process load did not converge");
  s->p0 = d0.T_real.translation();
  s->R_W_tcp = d0.T_nominal.linear();
  return [s](const Vec3& F_mill) -> Vec3 {
    nc::Loads l;
    l.gravity = s->gravity;
    l.tcp_tool.force = Vec3(F_mill.x(), -F_mill.y(), -F_mill.z());
    const nc::Deflection d = nc::predictDeflection(s->model, s->data, s->c, s->theta_m, l);
    if (!d.converged)
      throw std::runtime_error("robot compliance: the equilibrium did not converge");
    const Vec3 dt = s->R_W_tcp.transpose() * (d.T_real.translation() - s->p0);
    return Vec3(dt.x(), -dt.y(), -dt.z());
  };
}

LinearCompliance lineariseCompliance(const ComplianceFunction& full, const Vec3& F_ref,
                                     double step_N) {
  LinearCompliance l;
  l.F_ref = F_ref;
  l.delta_ref = full(F_ref);
  for (int i = 0; i < 3; ++i) {
    Vec3 G = F_ref;
    G[i] += step_N;
    l.C.col(i) = (full(G) - l.delta_ref) / step_N;
  }
  return l;
}

}  // namespace roprec
