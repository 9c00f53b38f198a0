#include "plugin/cli/robot_options.hpp"

#include "compensator/support/error.hpp"
#include "plugin/api/job_options.hpp"
#include "postproc/program.hpp"

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

std::vector<FrameDefinition> parseFrames(const std::string& text) { return framesFromText(text); }

void parseFrameTool(Args& args, JobOptions& opt) {
  if (const auto f = args.option("frame")) applyFrameOption(opt, *f);
  if (const auto t = args.option("tool")) applyToolOption(opt, *t);
}

void printJobNotes(CommandContext& ctx, const std::vector<std::string>& notes) {
  const std::string resolution = kResolutionPrefix;
  const std::string reading = postproc::kReadingNotePrefix;
  constexpr int kListedUnresolved = 20;
  int unresolved = 0;
  for (const auto& n : notes) {
    if (n.rfind(resolution, 0) == 0) {
      ctx.err << "roprec: note: " << n.substr(resolution.size()) << "\n";
    } else if (n.rfind(reading, 0) == 0) {
      ctx.err << "roprec: note: " << n.substr(reading.size()) << "\n";
    } else if (n.rfind("drill: ", 0) == 0) {  // holes the cell's single drill drills unasked
      ctx.err << "roprec: warning: " << n.substr(7) << "\n";
    } else if (n.rfind("robot card: ", 0) == 0) {
      ctx.err << "roprec: warning: " << n.substr(12) << "\n";
    } else if (n.rfind("--holes:", 0) == 0 || n.rfind("--force", 0) == 0) {
      ctx.err << "roprec: note: " << n << "\n";
    } else if (n.rfind(kUnresolvedPrefix, 0) == 0) {
      if (unresolved++ < kListedUnresolved) ctx.err << "roprec: warning: " << n << "\n";
    }
  }
  if (unresolved > kListedUnresolved) {
    ctx.err << "roprec: warning: and " << (unresolved - kListedUnresolved)
            << " more unresolved references (all in the JSON notes)\n";
  }
}

}  // namespace roprec::cli
