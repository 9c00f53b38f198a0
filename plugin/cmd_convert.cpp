/// `roprec convert PROGRAM [--to D] -o OUT`.
#include "compensator/error.hpp"
#include "plugin/cli.hpp"
#include "postproc/program.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext&) {
  const std::optional<std::string> out = args.option("o");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (pos.size() != 1 || !out) throw UsageError("convert needs PROGRAM and -o OUT");
  const postproc::Program p = postproc::readProgram(pos[0]);
  postproc::writeProgram(p, *out);
  return 0;
}

const CommandRegistration reg{{"convert", "a program through its reader and writer, or into another dialect",
                               "usage: roprec convert PROGRAM [--to krl|rapid|tp|csv|json] -o OUT\n", 61, run}};

}  // namespace
}  // namespace roprec::cli
