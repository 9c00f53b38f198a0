/// `roprec verify`: measured holes (CMM) against the prediction; optional registration and
/// re-identification of the joint stiffness with a new robot card.
#include <cmath>
#include <filesystem>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/report/verify_json.hpp"
#include "plugin/report/verify_report.hpp"

namespace roprec::cli {
namespace {

std::string um(double m, int decimals = 1) { return formatNumber(m * 1e6, decimals); }

std::string vecUm(const Vec3& v) {
  return "(" + um(v.x()) + ", " + um(v.y()) + ", " + um(v.z()) + ")";
}

void printStatistics(CommandContext& ctx, const VerifyResult& r) {
  if (!r.poses.poses.empty())
    ctx.out << "roprec verify: " << r.poses.poses.size() << " measured poses (" << r.poses.path
            << ", 3 equations each)\n";
  if (r.measured.holes.empty()) return;
  const VerificationSummary& s = r.summary;
  ctx.out << "roprec verify: " << r.measured.holes.size() << " measured holes, " << r.match.matched
          << " matched, " << s.holes << " verified\n";
  ctx.out << "  |deviation ⊥ axis| RMS [µm]: measured " << um(s.measured.rms) << ", predicted "
          << um(s.predicted.rms) << ", residual " << um(s.residual.rms)
          << " (max: " << um(s.measured.max) << ", " << um(s.predicted.max) << ", "
          << um(s.residual.max) << ")\n";
  // A correlation is undefined (NaN) with fewer than two holes or no spread along an axis.
  const auto corr = [](double v) {
    return std::isfinite(v) ? formatNumber(v, 3) : std::string("undefined");
  };
  ctx.out << "  explained share " << formatNumber(s.explained, 3) << "; inside the predicted 95 % "
          << "region " << s.inside << "/" << s.holes << " (coverage " << formatNumber(s.coverage, 3)
          << "); correlation x y z " << corr(s.correlation.x()) << " " << corr(s.correlation.y())
          << " " << corr(s.correlation.z()) << "\n";
  ctx.out << "  measured values (ISO 14253-1): " << s.conformance_proven << " conformance proven, "
          << s.nonconformance_proven << " non-conformance proven, " << s.no_decision
          << " no decision\n";
}

std::string mmTriple(const Vec3& v, double scale) {
  return formatNumber(v.x() * scale, 3) + " " + formatNumber(v.y() * scale, 3) + " " +
         formatNumber(v.z() * scale, 3);
}

/// The identified geometry: per joint origin and the tip, what moved and how well it is known.
void printGeometry(CommandContext& ctx, const IdentificationResult& id) {
  if (!id.geometry) return;
  int identified = 0;
  int total = 0;
  for (const IdentifiedParameter& q : id.parameters) {
    const bool geo =
        (q.name.size() > 2 && q.name[0] == 'j' && q.name[2] == '_') || q.name.rfind("tip_", 0) == 0;
    total += geo;
    identified += geo && q.identifiable;
  }
  ctx.out << "    geometry: " << identified << " of " << total
          << " components identified (prior 0.3 mm / 0.5 mrad, data-sheet class); the others "
             "keep their prior\n";
  for (size_t e = 0; e < 7; ++e) {
    const FrameError& f = e < 6 ? id.geometry->joints[e] : id.geometry->tool;
    ctx.out << "      "
            << (e < 6 ? "joint " + std::to_string(e + 1) + " origin" : std::string("tip"))
            << ": δxyz " << mmTriple(f.dxyz, 1e3) << " mm ± " << mmTriple(f.sigma_xyz, 1e3)
            << ", δrpy " << mmTriple(f.drpy, 1e3) << " mrad ± " << mmTriple(f.sigma_rpy, 1e3)
            << "\n";
  }
  for (const std::string& d : id.dependencies)
    ctx.out << "      dependent, prior kept: " << d << "\n";
}

void printIdentification(CommandContext& ctx, const VerifyResult& r) {
  if (!r.identification) return;
  const IdentificationResult& id = *r.identification;
  if (r.registration != Registration::kNone) {
    ctx.out << "  registration (" << registrationName(r.registration)
            << ", workobject axes): t = " << vecUm(id.registration.translation) << " ± "
            << vecUm(id.registration.translation_sigma) << " µm";
    if (r.registration == Registration::kRigid)
      ctx.out << ", ω = " << vecUm(id.registration.rotation) << " ± "
              << vecUm(id.registration.rotation_sigma) << " µrad";
    ctx.out << "\n";
  }
  ctx.out << "  identification: " << (id.converged ? "converged" : "NOT converged") << " in "
          << id.iterations << " iterations, condition number "
          << (std::isfinite(id.condition_number)
                  ? formatNumber(id.condition_number, 1)
                  : std::string("undefined (the measured holes identify no parameter)"))
          << "; residual RMS " << um(id.rms_prior) << " µm with the card -> " << um(id.rms_final)
          << " µm identified\n";
  if (!id.message.empty()) ctx.out << "    " << id.message << "\n";
  for (int j = 0; j < 6; ++j) {
    const auto jj = static_cast<size_t>(j);
    ctx.out << "    k" << j + 1 << " = " << formatNumber(id.compliance.k[j], 0) << " ± "
            << formatNumber(id.k_sigma[j], 0) << " N·m/rad ("
            << (id.joint_identified[jj] ? "identified, ρ = " : "not identifiable, prior kept, ρ = ")
            << formatNumber(id.parameters[jj].ratio, 3) << "; card "
            << formatNumber(r.prediction.context.robot.card.joints[jj].stiffness, 0) << ")\n";
  }
  printGeometry(ctx, id);
  for (const IdentifiedParameter& q : id.parameters) {
    if (q.name.rfind("tool_", 0) != 0) continue;
    const bool mass = q.name == "tool_mass";
    const double scale = mass ? 1.0 : 1e3;  // kg, mm
    ctx.out << "    " << q.name << " = " << formatNumber(q.value * scale, 3) << " ± "
            << formatNumber(q.sigma * scale, 3) << (mass ? " kg" : " mm") << " change ("
            << (q.identifiable ? "identified" : "not identifiable, cell value kept")
            << ", ρ = " << formatNumber(q.ratio, 3) << ")\n";
  }
}

void printValidation(CommandContext& ctx, const VerifyResult& r) {
  if (r.fit_check) {
    const FitCheck& f = *r.fit_check;
    ctx.out << "  fit check: residual " << formatNumber(f.rms_normalized, 2)
            << " × the measurement σ (χ² " << formatNumber(f.chi2, 1) << ", " << f.dof
            << " degrees of freedom, 99.9 % quantile " << formatNumber(f.chi2_999, 1)
            << "): " << (f.consistent ? "consistent with the noise" : "NOT consistent") << "\n";
  }
  if (r.validation) {
    const HeldOutValidation& v = *r.validation;
    ctx.out << "  held-out validation (" << v.folds << "-fold): expected residual after "
            << "calibration " << um(v.rms_calibrated) << " µm RMS; original card "
            << um(v.rms_original) << " µm RMS" << (v.better ? "" : " (NOT improved)") << "\n";
  }
}

/// Warnings that make the run exit 1: an inconsistent fit, a refused card.
int warnings(CommandContext& ctx, const VerifyResult& r) {
  int code = 0;
  if (r.fit_check && !r.fit_check->consistent) {
    ctx.err << "roprec: warning: " << r.fit_check->explanation << "\n";
    code = 1;
  }
  if (!r.card_refused.empty()) {
    ctx.err << "roprec: the calibrated card is not written: " << r.card_refused << "\n";
    code = 1;
  }
  return code;
}

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  VerifyJob job;
  job.job.holes = args.option("holes");
  const auto measured = args.option("measured");
  const auto poses = args.option("poses");
  const auto json_out = args.option("json");
  const auto report_out = args.option("report");
  const auto card_out = args.option("calibrate");
  const auto reg = args.option("register");
  const auto u = args.option("u-meas");
  const auto u_rot = args.option("u-rot");
  const auto cell_out = args.option("write-cell");
  const auto folds = args.option("folds");
  const auto identify = args.option("identify");
  const auto date = args.option("date");
  job.identify_tool = args.flag("identify-tool");
  const auto fail_on = args.option("fail-on");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (!measured && !poses)
    throw UsageError("give --measured MEASURED (CSV, PC-DMIS CSV or DMIS) and/or --poses POSES");
  if (measured && pos.size() != 1) throw UsageError("give exactly one PROGRAM file");
  if (pos.size() > 1) throw UsageError("give at most one PROGRAM file");
  if (!measured && !pos.empty() && !poses)
    throw UsageError(
        "a PROGRAM needs --measured (the holes measured on the part it drilled) or "
        "--poses (tracker poses of its targets)");
  if (measured) job.measured = *measured;
  if (poses) job.poses = *poses;
  job.calibrate = card_out.has_value();
  if (reg) {
    const auto r = registrationFromName(*reg);
    if (!r) throw UsageError("--register must be none, translation or rigid");
    job.registration = *r;
  }
  if (date) job.date = *date;
  if (u) job.u_measurement_um = parseNumberList(*u, 1, "--u-meas (µm)")[0];
  if (u_rot) {
    job.u_rotation_urad = parseNumberList(*u_rot, 1, "--u-rot (µrad)")[0];
    if (!(job.u_rotation_urad > 0)) throw UsageError("--u-rot must be > 0 µrad");
  }
  if (folds) {
    const double k = parseNumberList(*folds, 1, "--folds")[0];
    if (!(k >= 0 && k <= 100 && k == std::floor(k)))
      throw UsageError("--folds must be a whole number in [0, 100]");
    job.folds = static_cast<int>(k);
  }
  if (identify) {
    const auto s = identifySetFromName(*identify);
    if (!s || *s == IdentifySet::kNone)
      throw UsageError("--identify must be stiffness, geometry or all");
    job.identify = *s;
  }
  if (fail_on && *fail_on != "nonconformance")
    throw UsageError(
        "--fail-on takes nonconformance (exit 1 when a hole is proven non-conforming)");
  if (cell_out && !reg && !card_out)
    throw UsageError("--write-cell needs --register and/or --calibrate (nothing to write)");

  Progress progress(ctx, "predicting holes", 0);
  const VerifyResult r = verifyJob(*cell, pos.empty() ? std::string() : pos[0], job,
                                   [&](size_t done, size_t total) { progress.step(done, total); });
  progress.finish();
  for (const auto& f : r.failed) ctx.err << "roprec: " << f << "\n";
  if (!ctx.quiet) {
    for (const auto& n : r.notes) ctx.err << "roprec: note: " << n << "\n";
  }
  // render every text first, write only when all of them exist and nothing failed
  std::vector<std::pair<std::string, std::string>> out;
  if (json_out) out.emplace_back(*json_out, verifyJson(r).dump());
  if (report_out) out.emplace_back(*report_out, verifyReport(r));
  // a refused card is written neither itself nor as the new cell's robot
  const bool card_ok = card_out && r.card_refused.empty();
  if (card_ok)
    out.emplace_back(
        *card_out, calibratedCardText(
                       r, std::filesystem::path(measured ? *measured : *poses).filename().string(),
                       *card_out));
  if (cell_out && (!card_out || card_ok))
    out.emplace_back(*cell_out, calibratedCellText(r, *cell_out, card_ok ? *card_out : ""));
  if (!ctx.quiet) {
    printStatistics(ctx, r);
    printIdentification(ctx, r);
    printValidation(ctx, r);
  }
  if (!r.failed.empty()) {
    ctx.err << "roprec: " << r.failed.size() << " measured holes could not be predicted; nothing "
            << "written\n";
    return 1;
  }
  int code = warnings(ctx, r);
  for (const auto& [path, text] : out) writeFileAtomic(path, text);
  if (!ctx.quiet) {
    for (const auto& [path, text] : out) ctx.out << "  wrote " << path << "\n";
  }
  if (fail_on && r.summary.nonconformance_proven > 0) {
    ctx.err << "roprec: " << r.summary.nonconformance_proven
            << " holes proven non-conforming (ISO 14253-1; --fail-on nonconformance)\n";
    code = 1;
  }
  return code;
}

const CommandRegistration reg{
    {"verify", "measured holes (CMM) vs prediction; registration, re-identified robot card",
     "usage: roprec verify --cell CELL.xml PROGRAM --measured MEASURED [--holes HOLES.csv]\n"
     "                     [--poses POSES.csv]  |  roprec verify --cell CELL.xml [PROGRAM] --poses "
     "POSES.csv\n"
     "                     [--json OUT.json] [--report OUT.html] [--calibrate NEW_CARD.xml]\n"
     "                     [--register none|translation|rigid] [--identify-tool] [--u-meas UM]\n"
     "                     [--u-rot URAD]\n"
     "                     [--identify stiffness|geometry|all] [--folds K]\n"
     "                     [--write-cell NEW_CELL.xml] [--date YYYY-MM-DD] [--quiet]\n"
     "                     [--fail-on nonconformance]\n\n"
     "Compares the holes a CMM measured on a part drilled with PROGRAM against roprec's "
     "prediction.\n"
     "MEASURED: roprec CSV (id,x,y,z[,i,j,k][,u]), PC-DMIS CSV (TYPE,NAME,X,Y,Z,...) or DMIS "
     "output\n"
     "(FA(id)=FEAT/CIRCLE,...), recognised by content; positions in the cell's workobject frame, "
     "mm;\n"
     "u = standard measurement uncertainty per axis, µm (--u-meas, default 5, when the file has "
     "none).\n"
     "POSES (laser tracker / CMM): CSV id,j1..j6 (commanded, controller convention, deg),x,y,z\n"
     "(measured TCP, workobject mm)[,rx,ry,rz][,mass,com_x,com_y,com_z][,fx,fy,fz,mx,my,mz][,u]\n"
     "[,u_rot] (docs/contract.md); j1..j6 left empty: the pose is PROGRAM's target of that id "
     "(its\n"
     "predicted command joints). Each pose gives 3 equations and joins the holes in the fit;\n"
     "with rx,ry,rz (the measured TCP orientation, URDF rpy = fixed X-Y-Z, deg, workobject frame)\n"
     "3 more: the small rotation from the predicted to the measured orientation, σ per axis u_rot\n"
     "µrad (--u-rot, default 100, when the row has none). Without measured holes the cell\n"
     "calibrates from poses alone.\n"
     "Holes are matched by id; unknown ids and unmeasured holes are notes. --holes: the program's\n"
     "hole list (ids, nominal positions and axes); give it to verify a compensated program "
     "against\n"
     "the nominal holes, and to name the holes as the CMM does. The commanded joints of a\n"
     "hole are the prediction's (rigid IK of the programmed target).\n"
     "Per hole (⊥ the nominal hole axis): measured deviation e_meas, predicted δwork⊥, residual\n"
     "r = e_meas − δwork⊥, whether |r| lies inside the predicted 95 % region (U_work and the\n"
     "measurement), and the ISO 14253-1 decision on the measured value with U_meas = 2.4477 u.\n"
     "Statistics: RMS/mean/max of measured, predicted and residual; explained share\n"
     "1 − RMS(r)/RMS(e_meas); coverage of the 95 % region; correlation per workobject axis.\n"
     "--register: a part registration (translation, or rigid = translation + small rotation about "
     "the\n"
     "workobject origin) estimated jointly with the joint stiffness and removed from the measured\n"
     "positions before the comparison; printed with its σ.\n"
     "--calibrate NEW_CARD.xml: regularised Levenberg–Marquardt identification of the joint\n"
     "compliances on the nonlinear model (priors: 50 % for estimated card values, 10 % "
     "otherwise);\n"
     "writes the robot card with each identifiable joint's stiffness and source replaced\n"
     "(`identified: N holes from FILE by roprec verify (σ = …)`); unidentifiable joints keep the\n"
     "prior and are listed. Prints k ± σ, identifiability ρ = σ/σ_prior, the condition number.\n"
     "With the geometry identified, the card's <calibration> block holds it (per joint origin,\n"
     "the tip; σ from the posterior; source, number of observations, fit residual).\n"
     "The new card's urdf attribute points to the original URDF when it is not beside the card.\n"
     "--date YYYY-MM-DD: the <calibration date>; without it the UTC day of SOURCE_DATE_EPOCH\n"
     "when set, else of the measured file's modification time (docs/cards.md).\n"
     "--identify-tool: also identify the tool's mass and centre of mass (changes to the cell's\n"
     "<tool>, prior σ 2 kg and 20 mm), reported with their σ; the cell file is not rewritten.\n"
     "Every --calibrate is checked: the fit's χ² against the measurement σ (a residual above 2 σ\n"
     "RMS is a warning naming what the model cannot explain — a length scale, a drift with time —\n"
     "and exit 1), and a K-fold cross-validation (--folds, default 5; observation i in fold i mod "
     "K)\n"
     "prints the expected residual after calibration next to the original card's (registration\n"
     "re-estimated for both); a card whose held-out residual is not below the original's is not\n"
     "written (exit 1, reason stated).\n"
     "--identify: the robot parameters --calibrate moves: stiffness (the joint compliances),\n"
     "geometry (per joint origin δxyz/δrpy and the tip: the card's <calibration> block; priors\n"
     "0.3 mm / 0.5 mrad, data-sheet class), or all (default: compliances, plus the geometry when\n"
     "its held-out residual is below the compliances-alone one). Exactly dependent parameters\n"
     "(joint-1 origin vs the registration, joint-6 origin vs the tip, …) keep their prior and are\n"
     "printed with the combination that was identified; so are those the data cannot see.\n"
     "--write-cell NEW_CELL.xml: the cell with <part_registration> (where the registration found\n"
     "the part; the workobject kept) and <robot file=\"NEW_CARD.xml\"/> (with --calibrate): the\n"
     "next compensate uses both, whatever frame its program uses.\n"
     "--json: the verification JSON; --report: one self-contained HTML file (arrows per face,\n"
     "residual map, statistics, identified parameters).\n"
     "Outputs are written only when every measured hole was predicted. Exit 1 if some measured "
     "holes\n"
     "could not be predicted (listed, nothing written), if the fit is not consistent with the\n"
     "noise or the card was refused (warning on stderr), with --fail-on nonconformance when a\n"
     "measured hole is proven non-conforming (outputs written; a QA gate), 2 for bad input\n"
     "(FILE:LINE: what).\n",
     55, run}};

}  // namespace
}  // namespace roprec::cli
