/// `roprec convert PROGRAM [--to D] -o OUT`: a program through its own reader and writer
/// (byte-identical when nothing changed), or its targets into a new program in another dialect.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "postproc/convert.hpp"
#include "postproc/program.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  std::optional<std::string> out = args.option("o");
  if (!out) out = args.option("output");
  const std::optional<std::string> to = args.option("to");
  const std::optional<std::string> frames = args.option("frame");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (pos.size() != 1 || !out) throw UsageError("convert needs one PROGRAM and -o OUT");
  postproc::Program p = postproc::readProgram(pos[0]);
  if (frames) {
    std::istringstream in(*frames);
    std::string item;
    while (std::getline(in, item, ';')) {
      const std::size_t eq = item.find('=');
      if (eq == std::string::npos) throw UsageError("--frame expects REF=\"x y z a b c\"[;REF=...]");
      postproc::resolveFrame(p, item.substr(0, eq), parsePoseXyzAbc(item.substr(eq + 1), "--frame REF=\"x y z a b c\" (mm, deg, KUKA ABC)"));
    }
  }
  if (!to) {
    postproc::writeProgram(p, *out);
    return 0;
  }
  postproc::ConversionReport report;
  const auto files = postproc::convertProgram(p, postproc::dialectFromName(*to), *out, report);
  for (const auto& [path, bytes] : files) writeFileAtomic(path, bytes);
  if (!ctx.quiet) {
    // "p7: no configuration in the source; ..." repeated per target: print each message once with
    // the targets it concerns (first few named), in first-seen order
    std::vector<std::string> order;
    std::map<std::string, std::vector<std::string>> who;
    for (const std::string& n : report.notes) {
      const std::size_t c = n.find(": ");
      const std::string key = c == std::string::npos ? n : n.substr(c + 2);
      const std::string name = c == std::string::npos ? "" : n.substr(0, c);
      if (!who.count(key)) order.push_back(key);
      who[key].push_back(name);
    }
    for (const std::string& key : order) {
      const auto& names = who[key];
      if (names.size() == 1) {
        ctx.err << "roprec: note: " << (names[0].empty() ? "" : names[0] + ": ") << key << "\n";
        continue;
      }
      ctx.err << "roprec: note: " << key << " (" << names.size() << " items: ";
      for (size_t i = 0; i < std::min<size_t>(names.size(), 3); ++i) ctx.err << (i ? ", " : "") << names[i];
      ctx.err << (names.size() > 3 ? ", ...)" : ")") << "\n";
    }
  }
  for (const std::string& s : report.skipped) ctx.err << "roprec: not converted: " << s << "\n";
  return report.skipped.empty() ? 0 : 1;
}

const CommandRegistration reg{
    {"convert", "a program through its own reader/writer, or its targets into another dialect",
     "usage: roprec convert PROGRAM [--to krl|rapid|tp|csv|json] -o OUT [--frame 'REF=x y z a b c[;...]']\n\n"
     "Without --to: PROGRAM is read and written back through its own reader and writer; the output\n"
     "is byte-identical to the input (KRL: OUT names the .src, the .dat is written beside it).\n"
     "With --to: the program's Cartesian targets are written as a new, minimal program in that\n"
     "dialect (KRL: OUT.src + OUT.dat). Configuration is carried at the branch level (shoulder,\n"
     "elbow, wrist); joint targets go only into csv/json (joint conventions differ between vendors);\n"
     "items that cannot be converted are listed and the exit code is 1. Frames that the output must\n"
     "state by value but the program does not define are given with --frame (mm, deg, KUKA ABC).\n",
     61, run}};

}  // namespace
}  // namespace roprec::cli
