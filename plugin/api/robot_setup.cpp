/// Robot + cell + tool + stiffness override for the per-pose calls (plugin/api/robot_setup.hpp).
#include "plugin/api/robot_setup.hpp"

#include <cstdio>

#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"

namespace roprec::api {

nc::ToolAttachment toolOf(const CellSpec& cell) {
  nc::ToolAttachment tool;
  tool.T_flange_tcp = cell.tool.T_flange_tcp;
  tool.mass = cell.tool.mass;
  tool.com = cell.tool.com;
  tool.inertia = cell.tool.inertia;
  return tool;
}

RobotSetup loadRobotSetup(const RobotSetupRequest& request) {
  RobotSetup s;
  RobotRequest req;
  if (request.cell) {
    s.cell = loadCell(*request.cell);
    req = s.cell->robot;
    s.tool = toolOf(*s.cell);
  }
  if (request.robot) req = RobotRequest{*request.robot, "", ""};
  if (request.base_link) req.base_link = *request.base_link;
  if (request.tip_link) req.tip_link = *request.tip_link;
  if (req.robot.empty()) throw UsageError("give --robot NAME|robot.xml|file.urdf (or --cell)");
  try {
    s.robot = loadRobot(req);
  } catch (const InputError& e) {
    if (e.file().empty() && s.cell && !request.robot) {
      throw InputError(s.cell->file, s.cell->robot_line, e.message());
    }
    throw;
  }
  if (request.stiffness) overrideStiffness(s, *request.stiffness);
  return s;
}

void overrideStiffness(RobotSetup& setup, const nc::Vec6& k, const std::string& name,
                       const std::string& source) {
  for (int i = 0; i < 6; ++i) {
    if (!(k[i] > 0)) {
      throw InputError("", 0,
                       name + ": k" + std::to_string(i + 1) + " must be > 0 N m/rad, got " +
                           std::to_string(k[i]));
    }
    setup.robot.card.joints[static_cast<size_t>(i)].stiffness = k[i];
    setup.robot.card.joints[static_cast<size_t>(i)].source = source;
  }
  setup.robot.card.has_stiffness = true;
}

std::vector<std::string> limitViolations(const ChainDescription& chain, const nc::Vec6& q) {
  std::vector<std::string> out;
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(i)];
    if (q[i] < j.lower - 1e-12 || q[i] > j.upper + 1e-12) {
      out.push_back(j.name + " = " + cFixed(q[i] / kDeg, 3) + " deg (limits " +
                    cFixed(j.lower / kDeg, 3) + " .. " + cFixed(j.upper / kDeg, 3) + " deg)");
    }
  }
  return out;
}

void requireWithinLimits(const ChainDescription& chain, const nc::Vec6& q,
                         const std::string& what) {
  const std::vector<std::string> viol = limitViolations(chain, q);
  if (!viol.empty()) throw InputError("", 0, what + " outside the joint limits: " + viol.front());
}

}  // namespace roprec::api
