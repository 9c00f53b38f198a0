#include "plugin/cli/robot_options.hpp"

#include <cstdio>

#include "compensator/support/error.hpp"
#include "plugin/api/json.hpp"

namespace roprec::cli {

RobotSetup loadRobotSetup(Args& args) {
  RobotSetup s;
  const auto robot = args.option("robot");
  const auto cell = args.option("cell");
  const auto base = args.option("base");
  const auto tip = args.option("tip");
  const auto stiffness = args.option("stiffness");
  RobotRequest req;
  if (cell) {
    s.cell = loadCell(*cell);
    req = s.cell->robot;
    s.tool.T_flange_tcp = s.cell->tool.T_flange_tcp;
    s.tool.mass = s.cell->tool.mass;
    s.tool.com = s.cell->tool.com;
    s.tool.inertia = s.cell->tool.inertia;
  }
  if (robot) req = RobotRequest{*robot, "", ""};
  if (base) req.base_link = *base;
  if (tip) req.tip_link = *tip;
  if (req.robot.empty()) throw UsageError("give --robot NAME|robot.xml|file.urdf (or --cell)");
  try {
    s.robot = loadRobot(req);
  } catch (const InputError& e) {
    if (e.file().empty() && s.cell && !robot) {
      throw InputError(s.cell->file, s.cell->robot_line, e.message());
    }
    throw;
  }
  if (stiffness) {
    const Eigen::VectorXd k = parseNumberList(*stiffness, 6, "--stiffness (k1 .. k6, N m/rad)");
    for (int i = 0; i < 6; ++i) {
      if (!(k[i] > 0)) {
        throw InputError("", 0, "--stiffness: k" + std::to_string(i + 1) + " must be > 0 N m/rad, got " +
                                    std::to_string(k[i]));
      }
      s.robot.card.joints[static_cast<size_t>(i)].stiffness = k[i];
      s.robot.card.joints[static_cast<size_t>(i)].source = "command line --stiffness";
    }
    s.robot.card.has_stiffness = true;
  }
  return s;
}

std::vector<std::string> limitViolations(const ChainDescription& chain, const nc::Vec6& q) {
  std::vector<std::string> out;
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(i)];
    if (q[i] < j.lower - 1e-12 || q[i] > j.upper + 1e-12) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s = %.3f deg (limits %.3f .. %.3f deg)", j.name.c_str(), q[i] / kDeg,
                    j.lower / kDeg, j.upper / kDeg);
      out.emplace_back(buf);
    }
  }
  return out;
}

Json poseJson(const Pose& T) {
  Json j = Json::object();
  j.set("position_mm", Json::vector(T.translation() * 1e3, 6));
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
  j.set("abc_deg", Json::vector(zyxFromRotation(T.linear()) / kDeg, 6));
  return j;
}

}  // namespace roprec::cli
