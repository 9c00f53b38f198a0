/// `roprec robots`: the bundled robots, with the source of every number the card carries.
#include "plugin/api/robots.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/report/robots_output.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  const bool as_json = args.flag("json");
  const bool all = args.flag("all");
  args.finish();
  const RobotList robots = robotList(bundledRobotCards());
  if (as_json) {
    ctx.out << robots.json.dump();
  } else {
    ctx.out << (all ? robots.text : robots.summary);
  }
  return 0;
}

const CommandRegistration reg{
    {"robots", "list the bundled robots and the sources of their numbers",
     "usage: roprec robots [--all | --json]\n\n"
     "Lists the bundled robots (robots/<name>/robot.xml), one line each: vendor, model, payload,\n"
     "ISO 9283 repeatability and whether the joint stiffness is published or estimated. --all:\n"
     "the joint stiffness and where every number comes from; --json: all of it as JSON. Numbers\n"
     "whose source begins with 'estimate:' are estimates (marked ESTIMATE / \"estimate\": true).\n",
     10, run}};

}  // namespace
}  // namespace roprec::cli
