/// `roprec card new|check|import-calibration|export-urdf`: scaffold a robot card for a URDF, check
/// a card, take a calibrated URDF's geometry into a card and write the calibrated URDF
/// (docs/cards.md).
#include "compensator/support/error.hpp"
#include "plugin/api/card_tools.hpp"
#include "plugin/cli/cli.hpp"

namespace roprec::cli {
namespace {

double positiveNumber(const std::string& text, const std::string& what) {
  const double v = parseNumberList(text, 1, what)[0];
  if (!(v > 0)) throw UsageError(what + " must be > 0, got " + text);
  return v;
}

int runNew(Args& args, CommandContext& ctx) {
  CardScaffoldRequest req;
  const auto urdf = args.option("urdf");
  const auto out = args.option("o");
  if (const auto v = args.option("vendor")) {
    req.vendor = vendorFromString(*v);
    if (*req.vendor == Vendor::kGeneric) throw UsageError("--vendor must be KUKA, ABB or FANUC");
  }
  if (const auto m = args.option("model")) req.model = *m;
  if (const auto p = args.option("payload-kg")) req.payload_kg = positiveNumber(*p, "--payload-kg");
  if (const auto m = args.option("mass-kg")) req.mass_kg = positiveNumber(*m, "--mass-kg");
  args.finish();
  if (!urdf) throw UsageError("card new needs --urdf FILE.urdf");
  if (!out || *out == "-")
    throw UsageError(
        "card new needs -o robot.xml (a file: the card names its URDF relative to its folder)");
  req.urdf = *urdf;
  req.card_path = *out;
  const CardNewResult r = cardNew(req);
  emit(ctx, *out, r.card.xml);
  if (!ctx.quiet) ctx.err << r.summary;
  ctx.out << "wrote " << *out << "\n";
  return 0;
}

int runCheck(Args& args, CommandContext& ctx, const std::vector<std::string>& files) {
  const auto cell = args.option("cell");
  args.finish();
  if (files.size() > 1) throw UsageError("card check takes one robot.xml");
  const CardCheckResult r = cardCheck(files.empty() ? std::string() : files[0], cell);
  ctx.out << r.table;
  ctx.err << r.findings;
  return r.exit_code;
}

/// card import-calibration --urdf CALIBRATED.urdf CARD.xml -o NEW.xml
int runImport(Args& args, CommandContext& ctx, const std::vector<std::string>& files) {
  const auto urdf = args.option("urdf");
  const auto out = args.option("o");
  args.finish();
  if (files.size() != 1) throw UsageError("card import-calibration takes one robot.xml");
  if (!urdf) throw UsageError("card import-calibration needs --urdf CALIBRATED.urdf");
  if (!out || *out == "-")
    throw UsageError("card import-calibration needs -o NEW.xml (a file: the card names its URDF)");
  const CardImportResult r = cardImportCalibration(files[0], *urdf, *out);
  emit(ctx, *out, r.card_text);
  if (!ctx.quiet) ctx.err << r.summary;
  ctx.out << "wrote " << *out << "\n";
  return 0;
}

/// card export-urdf CARD.xml -o real.urdf
int runExport(Args& args, CommandContext& ctx, const std::vector<std::string>& files) {
  const auto out = args.option("o");
  args.finish();
  if (files.size() != 1) throw UsageError("card export-urdf takes one robot.xml");
  if (!out) throw UsageError("card export-urdf needs -o real.urdf (or -o - for stdout)");
  const std::string text = cardExportUrdf(files[0]);
  emit(ctx, *out, text);
  if (*out != "-") ctx.out << "wrote " << *out << "\n";
  return 0;
}

int run(Args& args, CommandContext& ctx) {
  // options of both sub-commands are read by the one that owns them; peek at the first word
  Args probe = args;
  probe.option("urdf");
  probe.option("o");
  probe.option("vendor");
  probe.option("model");
  probe.option("payload-kg");
  probe.option("mass-kg");
  probe.option("cell");
  const std::vector<std::string> words = probe.positionals();
  if (!words.empty() && (words[0] == "import-calibration" || words[0] == "export-urdf")) {
    Args rest = args;
    const auto urdf = rest.option("urdf");
    const auto out = rest.option("o");
    std::vector<std::string> files = rest.positionals();
    files.erase(files.begin());
    std::vector<std::string> opts;
    if (urdf) opts.insert(opts.end(), {"--urdf", *urdf});
    if (out) opts.insert(opts.end(), {"-o", *out});
    Args sub(opts);
    return words[0] == "export-urdf" ? runExport(sub, ctx, files) : runImport(sub, ctx, files);
  }
  if (words.empty() || (words[0] != "new" && words[0] != "check"))
    throw UsageError(
        "give a sub-command: card new, card check, card import-calibration or card export-urdf");
  if (words[0] == "new") {
    if (words.size() > 1) throw UsageError("unexpected argument '" + words[1] + "'");
    Args rest = args;
    rest.positionals();  // "new"
    return runNew(rest, ctx);
  }
  const auto cell = args.option("cell");
  std::vector<std::string> files = args.positionals();
  files.erase(files.begin());  // "check"
  Args rest(cell ? std::vector<std::string>{"--cell", *cell} : std::vector<std::string>{});
  return runCheck(rest, ctx, files);
}

const CommandRegistration reg{
    {"card", "robot cards: card new, check, import-calibration, export-urdf",
     "usage: roprec card new --urdf FILE.urdf [--vendor KUKA|ABB|FANUC] [--model TEXT]\n"
     "                       [--payload-kg KG] [--mass-kg KG] -o robot.xml\n"
     "       roprec card check robot.xml [--cell CELL.xml]\n"
     "       roprec card check --cell CELL.xml\n"
     "       roprec card import-calibration --urdf CALIBRATED.urdf robot.xml -o NEW.xml\n"
     "       roprec card export-urdf robot.xml -o real.urdf\n\n"
     "card new finds the serial 6R chain of the URDF, the base link (FANUC: the World frame\n"
     "'base' at J2 height when the URDF has it) and the flange link (the first of tool0,\n"
     "flange with z out of the flange: ROS-Industrial's 'flange' is x-out and is skipped), the\n"
     "vendor's joint signs and the FANUC J2/J3 coupling, and writes a complete card: joint\n"
     "stiffness from the published class data (KUKA KR500 set for 120-500 kg arms, times\n"
     "payload/120 kg below), position gain 40 1/s, repeatability 0.08 mm, link inertials from\n"
     "the URDF unless missing or ROS-Industrial placeholders (then a class estimate from the\n"
     "robot mass, --mass-kg or 34 kg x payload^0.7), absolute accuracy AP 1.0 mm. Every number\n"
     "has a source; estimates are marked 'estimate:'. The vendor and payload are read from the\n"
     "URDF robot name when not given. The URDF is referenced relative to the card's folder.\n"
     "What you must still confirm is printed on stderr.\n\n"
     "card check loads the card and checks it against its URDF and the vendor conventions:\n"
     "flange z out of the flange, the flange orientation at the vendor's home pose, the base\n"
     "frame (FANUC World at J2 height), joint signs and J2/J3 coupling, joint ranges,\n"
     "stiffness within 10x (warning) / 100x (error) of the class, repeatability, placeholder or\n"
     "implausible link masses; with --cell also the tool mass against the rated payload.\n"
     "Prints a table on stdout and FILE:LINE findings with hints on stderr. predict and\n"
     "compensate run the same checks when they load a card. A URDF an external calibration\n"
     "wrote passes: axes and the flange up to 5 mrad (a warning to 20 mrad) and FANUC's J2\n"
     "height up to 1 mm (a warning to 5 mm) off the convention count as calibration offsets;\n"
     "a card's <calibration> offsets are checked against 1 mm / 5 mrad (warning) and 5 mm /\n"
     "20 mrad (error).\n\n"
     "card import-calibration derives the card's <calibration> block (docs/cards.md section 5)\n"
     "from a calibrated URDF of the same robot: each joint origin's error in its nominal joint\n"
     "frame (a tilted axis vector becomes an origin rotation), the flange error; a base error\n"
     "cannot be told from joint 1's in a URDF and goes into joint 1. The old block is replaced,\n"
     "every other byte of the card kept. card export-urdf writes the card's URDF with the\n"
     "calibration in its joint origins (the real robot, for other tools).\n\n"
     "exit codes: 0 ok or warnings only, 2 errors (or bad input)\n",
     12, run}};

}  // namespace
}  // namespace roprec::cli
