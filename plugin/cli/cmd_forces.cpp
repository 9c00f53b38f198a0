/// `roprec forces`: the process forces of a cell alone (drilling, milling or a given wrench):
/// steady values as JSON, curves vs depth (drilling) or vs cutter angle (milling) as CSV, and the
/// single-test calibration of kst0/ksa0.
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/temp_spill.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/report/forces_output.hpp"

namespace roprec::cli {
namespace {

constexpr double kMm = 1e-3;

/// `--calibrate "Fa_N=... M_Nm=..."` (Fz_N is accepted for Fa_N).
DrillingMeasurement parseCalibration(const std::string& text) {
  DrillingMeasurement m;
  bool has_f = false;
  bool has_m = false;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) {
    const auto eq = tok.find('=');
    if (eq == std::string::npos)
      throw UsageError("--calibrate expects \"Fa_N=... M_Nm=...\", got '" + tok + "'");
    const std::string key = tok.substr(0, eq);
    const auto v = parseNumber(tok.substr(eq + 1));
    if (!v || !(*v > 0))
      throw InputError(
          "", 0,
          "--calibrate: " + key + " must be a positive number, got '" + tok.substr(eq + 1) + "'");
    if (key == "Fa_N" || key == "Fz_N") {
      m.thrust = *v;
      has_f = true;
    } else if (key == "M_Nm") {
      m.torque = *v;
      has_m = true;
    } else {
      throw UsageError("--calibrate: unknown key '" + key + "' (Fa_N, M_Nm)");
    }
  }
  if (!has_f || !has_m) throw UsageError("--calibrate needs both Fa_N=... and M_Nm=...");
  return m;
}

/// Reads the numeric options into the request (mm and µm/N on the command line).
void parseNumbers(ForcesRequest& req, const std::optional<std::string>& step_mm,
                  const std::optional<std::string>& points,
                  const std::optional<std::string>& axial) {
  if (step_mm) {
    const auto v = parseNumber(*step_mm);
    if (!v || !(*v > 0)) throw InputError("", 0, "--step-mm must be a positive number");
    req.step = *v * kMm;
  }
  if (points) {
    const auto v = parseNumber(*points);
    if (!v || !(*v >= 1 && *v <= 100000) || *v != std::floor(*v))
      throw InputError("", 0, "--points must be an integer >= 1");
    req.points = static_cast<int>(*v);
  }
  if (axial) {
    const auto v = parseNumber(*axial);
    if (!v || !(*v >= 0))
      throw InputError("", 0, "--axial-compliance-um-per-N must be a number >= 0");
    req.axial_compliance = *v * 1e-6;
  }
}

/// Writes everything `spill` holds to standard output, 1 MB at a time (before the staged files
/// are renamed, as main() writes it); a failed write is main()'s "cannot write to standard
/// output" error.
void copyToStdout(TempSpill& spill) {
  spill.replay(
      [](std::string_view v) {
        if (const int e = writeStdout(v); e != 0) {
          throw std::runtime_error("cannot write to standard output: " + platform::errorText(e) +
                                   "; nothing written");
        }
      },
      std::size_t{1} << 20U);
}

/// `--program` (milling): the JSON written as the path's blocks of points arrive, into its staged
/// file or, for standard output, a temporary file copied to it at the end (with the CSV before it
/// when that goes to standard output too); the curve CSV (from the result before the path) first.
ForcesResult runProgram(CommandContext& ctx, const ForcesRequest& req,
                        const std::optional<std::string>& csv_path,
                        const std::optional<std::string>& json_path) {
  const bool to_stdout = !json_path || json_path->empty() || *json_path == "-";
  std::optional<TempSpill> spill;
  if (to_stdout) spill.emplace("standard output");
  const auto stream = [&](const ByteWriter& write) {
    ForcesJsonStream json(write);
    ForcesPathSink sink;
    sink.head = [&](const ForcesResult& head) {
      if (csv_path) {
        std::string csv = forcesOutput(head).curve_csv;
        if (spill && (csv_path->empty() || *csv_path == "-")) {
          spill->write(csv);
        } else {
          emit(ctx, *csv_path, csv);
        }
      }
      (void)json.head(head);
    };
    sink.points = [&](const MillingCompensationResult& block) { json.points(block); };
    ForcesResult r = processForces(req, sink);
    json.finish();
    write("\n");
    return r;
  };
  if (spill) {
    ForcesResult r = stream([&](std::string_view bytes) { spill->write(bytes); });
    copyToStdout(*spill);
    return r;
  }
  ForcesResult r;
  writeFileAtomicStream(*json_path, [&](const ByteWriter& write) { r = stream(write); });
  return r;
}

int run(Args& args, CommandContext& ctx) {
  const auto cell_path = args.option("cell");
  const auto csv_path = args.option("csv");
  const auto json_path = args.option("json");
  const auto calibrate = args.option("calibrate");
  const auto out_xml = args.option("o");
  const auto step_mm = args.option("step-mm");
  const auto points = args.option("points");
  const auto axial = args.option("axial-compliance-um-per-N");
  const auto joints = args.option("joints");
  const auto program = args.option("program");
  const auto tool = args.option("tool");
  const int threads = parseThreadsOption(args);
  args.finish();
  if (!cell_path) throw UsageError("give --cell CELL.xml");
  ForcesRequest req;
  req.cell = *cell_path;
  parseNumbers(req, step_mm, points, axial);
  if (calibrate) req.calibrate = parseCalibration(*calibrate);
  if (joints && cellIsMilling(req.cell))
    req.joints = parseJointsDeg(*joints);  // read for milling only
  req.program = program;
  req.tool = tool;
  req.calibrated_cell = out_xml.has_value();
  req.curve = csv_path.has_value();
  req.threads = resolvedThreads(threads);
  if (req.program && cellIsMilling(req.cell)) {  // the path streamed (else the errors of below)
    const ForcesResult r = runProgram(ctx, req, csv_path, json_path);
    for (const std::string& u : r.unstable) ctx.err << "roprec: " << u << "\n";
    return r.converged && r.unstable.empty() ? 0 : 1;
  }

  const ForcesResult r = processForces(req);
  const ForcesOutput o = forcesOutput(r);
  const std::string json_text = o.json.dump() + "\n";
  if (csv_path) emit(ctx, *csv_path, o.curve_csv);
  if (out_xml) emit(ctx, *out_xml, r.calibrated_cell);
  if (json_path) {
    emit(ctx, *json_path, json_text);
  } else {
    ctx.out << json_text;
  }
  for (const std::string& u : r.unstable) ctx.err << "roprec: " << u << "\n";
  return r.converged && r.unstable.empty() ? 0 : 1;
}

const CommandRegistration reg{
    {"forces", "process forces of a cell (drilling, milling, wrench); single-test calibration",
     "usage: roprec forces --cell CELL.xml [--csv F.csv] [--json F.json] [--step-mm S]\n"
     "                     [--calibrate \"Fa_N=... M_Nm=...\" [-o|--output OUT.xml]] [--points "
     "N]\n"
     "                     [--axial-compliance-um-per-N C] [--joints \"j1 .. j6\"] [--program "
     "P.src]\n"
     "                     [--tool N] [--threads N]\n\n"
     "Computes the process forces of the cell's <process> (the robot is loaded only with "
     "--joints).\n"
     "  drilling: steady thrust, torque, rotating runout force Fr, per-lip forces, chisel share, "
     "the wrench\n"
     "            on the TCP in the tool frame (z into the material: force z = -thrust, torque z = "
     "-M), the\n"
     "            machining-deviation budget (U_mach, k = 2.45: 2-D radial 95 %); --csv writes "
     "depth_mm, "
     "engaged_radius_mm,\n"
     "            Fa_N, Ft_N, M_Nm, Fr_N through entry, steady cut and breakthrough.\n"
     "  milling:  immersion, h_m, revolution-mean and peak forces; --csv writes angle_deg, Fx_N, "
     "Fy_N,\n"
     "            Fz_N, Fxy_N over one revolution. With <coupling compliance_um_per_N=...> or "
     "--joints (deg:\n"
     "            the cell robot's own deflection at that pose) the coupled force/deflection "
     "solve (Newton on\n"
     "            r = delta - C(F(delta)), line search) over --points path points (default 10): "
     "per "
     "point status,\n"
     "            iterations, residual_um, loop_gain; --csv then writes vs the edge angle the "
     "nominal and the\n"
     "            corrected force (Fx/Fy/Fz/Fxy _nom_N and _N) and the TCP movement dx/dy/dz_um of "
     "the last point.\n"
     "            --program P.src: every linear point of the program: cutting true/false and why "
     "(speed, depth\n"
     "            vs <stock top_z_mm>), the coupled solve with the robot at the point, the "
     "surface error\n"
     "            normal to the wall, the regenerative and mode-coupling chatter limits.\n"
     "  wrench:   echoes the given tool-frame wrench.\n"
     "--axial-compliance-um-per-N (drilling): the feed absorbed by an axial compliance C at the "
     "TCP, one\n"
     "            quasi-static step per revolution (entry, steady cut, breakthrough lunge); the "
     "CSV is then\n"
     "            per revolution with feed_mm and dz_um columns.\n"
     "--tool N: the drill or mill of the cell's tool table (<drill tool=\"N\">, <mill "
     "tool=\"N\">: its\n"
     "geometry, cut and TCP); needed when the table holds several; with --program the program's "
     "active\n"
     "tool selects the mill of each point instead.\n"
     "--threads N (with --program): worker threads of the path's two pipelined chains (0 = every\n"
     "core; default 1); the output is byte-identical for any N. The path's points are written a\n"
     "block at a time as they are computed (on standard output through a temporary file, written\n"
     "out once the whole path is done); a KUKA KRL program, an ABB RAPID module or a FANUC TP\n"
     "program is read by windows, so memory does not grow with its number of points (a RAPID\n"
     "module's robtargets declared by name stay, ~500 B each; a TP program's /MN is read again\n"
     "behind its /POS).\n"
     "--calibrate identifies kst0 and ksa0 from one measured thrust and torque at the cell's "
     "diameter and\n"
     "feed; -o OUT.xml writes a copy of the cell with the calibrated <coefficients> "
     "(atomically).\n"
     "Exit 0 done; 1 some coupled points did not converge (listed with their status); 2 bad "
     "input (nothing\n"
     "written).\n",
     40, run}};

}  // namespace
}  // namespace roprec::cli
