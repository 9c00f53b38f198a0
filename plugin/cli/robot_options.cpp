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

void parseFrameTool(Args& args, JobOptions& opt) {
  if (const auto f = args.option("frame")) {
    if (*f == "cell") {
      opt.frame_cell = true;
    } else if (f->find('=') != std::string::npos) {
      opt.frames = parseFrames(*f);
    } else {
      opt.frame_pose = parsePoseXyzAbc(*f, "--frame \"x y z a b c\" (mm, deg, KUKA ABC) or cell");
    }
  }
  if (const auto t = args.option("tool")) {
    if (*t != "program" && *t != "cell") throw UsageError("--tool must be program or cell");
    opt.tool = *t;
  }
}

void printJobNotes(CommandContext& ctx, const std::vector<std::string>& notes) {
  const std::string resolution = kResolutionPrefix;
  for (const auto& n : notes) {
    if (n.rfind(resolution, 0) == 0) {
      ctx.err << "roprec: note: " << n.substr(resolution.size()) << "\n";
    } else if (n.rfind("robot card: ", 0) == 0) {
      ctx.err << "roprec: warning: " << n.substr(12) << "\n";
    } else if (n.rfind("--holes:", 0) == 0 || n.rfind("--force", 0) == 0) {
      ctx.err << "roprec: note: " << n << "\n";
    }
  }
}

}  // namespace roprec::cli
