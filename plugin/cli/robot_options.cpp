#include "plugin/cli/robot_options.hpp"

#include <sstream>

#include "compensator/support/error.hpp"

namespace roprec::cli {

RobotSetup loadRobotFromArgs(Args& args) {
  RobotSetupRequest req;
  req.robot = args.option("robot");
  req.cell = args.option("cell");
  req.base_link = args.option("base");
  req.tip_link = args.option("tip");
  const auto stiffness = args.option("stiffness");
  RobotSetup s = loadRobotSetup(req);
  if (stiffness) {
    const nc::Vec6 k = parseNumberList(*stiffness, 6, "--stiffness (k1 .. k6, N m/rad)");
    overrideStiffness(s, k, "--stiffness", "command line --stiffness");
  }
  return s;
}

std::vector<FrameDefinition> parseFrames(const std::string& text) {
  std::vector<FrameDefinition> frames;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ';')) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) throw UsageError("--frame expects REF=\"x y z a b c\"[;REF=...]");
    frames.push_back(
        {item.substr(0, eq),
         parsePoseXyzAbc(item.substr(eq + 1), "--frame REF=\"x y z a b c\" (mm, deg, KUKA ABC)")});
  }
  return frames;
}

}  // namespace roprec::cli
