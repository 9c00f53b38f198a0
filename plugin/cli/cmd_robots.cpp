/// `roprec robots`: the bundled robots, with the source of every number the card carries.
#include "plugin/api/robots.hpp"
#include "plugin/cli/cli.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  const bool as_json = args.flag("json");
  args.finish();
  const RobotList robots = bundledRobotList();
  if (as_json) {
    ctx.out << robots.json.dump();
  } else {
    ctx.out << robots.text;
  }
  return 0;
}

const CommandRegistration reg{
    {"robots", "list the bundled robots and the sources of their numbers",
     "usage: roprec robots [--json]\n\n"
     "Lists the bundled robots (robots/<name>/robot.xml): vendor, model, ISO 9283\n"
     "repeatability, joint stiffness and where every number comes from. Numbers whose\n"
     "source begins with 'estimate:' are estimates (marked ESTIMATE / \"estimate\": true).\n",
     10, run}};

}  // namespace
}  // namespace roprec::cli
