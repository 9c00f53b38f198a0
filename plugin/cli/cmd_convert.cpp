/// `roprec convert PROGRAM [--to D] -o OUT`: a program through its own reader and writer
/// (byte-identical when nothing changed), or its targets into a new program in another dialect.
#include "compensator/support/error.hpp"
#include "plugin/api/convert.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  std::optional<std::string> out = args.option("o");
  const std::optional<std::string> to = args.option("to");
  const std::optional<std::string> frames = args.option("frame");
  const bool verbose = args.flag("verbose");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (pos.size() != 1 || !out) throw UsageError("convert needs one PROGRAM and -o OUT");
  ConvertRequest req;
  req.program = pos[0];
  req.output = *out;
  req.to = to;
  if (frames) req.frames = parseFrames(*frames);
  req.all_lines = verbose;
  const ConvertResult r = convertProgramFile(req);
  if (!ctx.quiet) {
    for (const std::string& n : r.notes) ctx.err << "roprec: note: " << n << "\n";
  }
  for (const std::string& s : r.not_carried) ctx.err << "roprec: not carried: " << s << "\n";
  for (const std::string& s : r.skipped) ctx.err << "roprec: not converted: " << s << "\n";
  return r.skipped.empty() ? 0 : 1;
}

const CommandRegistration reg{
    {"convert", "a program through its own reader/writer, or its targets into another dialect",
     "usage: roprec convert PROGRAM [--to krl|rapid|tp|csv|json] -o OUT [--frame 'REF=x y z a b "
     "c[;...]']\n"
     "                      [--verbose]\n\n"
     "Without --to: PROGRAM is read and written back through its own reader and writer; the "
     "output\n"
     "is byte-identical to the input (KRL: OUT names the .src, the .dat is written beside it).\n"
     "With --to: the program's Cartesian targets are written as a new, minimal program in that\n"
     "dialect (KRL: OUT.src + OUT.dat). Configuration is carried at the branch level (shoulder,\n"
     "elbow, wrist); joint targets go only into csv/json (joint conventions differ between "
     "vendors);\n"
     "items that cannot be converted are listed and the exit code is 1. Every other instruction "
     "the\n"
     "new program does not carry (WAIT/WaitTime, I/O, spindle and other calls, control flow) is\n"
     "listed on stderr as 'not carried: FILE:LINE: text (kind)', and so is each zone mapping\n"
     "('zone z10 -> C_DIS at FILE:LINES'); unused external axes are written 9E+09 in RAPID.\n"
     "A repeated instruction or zone is listed once with its count and its first line numbers\n"
     "(about 1 KB a notice); --verbose lists every line number.\n"
     "Frames that the output must\n"
     "state by value but the program does not define are given with --frame (mm, deg, KUKA ABC).\n",
     61, run}};

}  // namespace
}  // namespace roprec::cli
