#include "plugin/api/milling_job.hpp"

#include <algorithm>
#include <iterator>
#include <optional>
#include <span>

#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "postproc/program.hpp"

namespace roprec::api {

bool cellIsMilling(const std::string& cell_path) {
  const CellSpec cell = loadCell(cell_path);
  return cell.has_process && cell.process.str("type") == "milling";
}

namespace {

std::string millTable(const ProcessSpec& spec) {
  std::string t;
  for (const MillingSpec& m : spec.mills) t += (t.empty() ? "" : ", ") + millLabel(m);
  return t;
}

/// The mill of every path point (the motions `motions` of `prog`): the one its active tool
/// selects (docs/process.md §8, tool table); all 0 for a single mill, which mills with one tool.
std::vector<int> millsOfPath(const ProcessSpec& spec, const postproc::Program& prog,
                             const std::vector<int>& motions) {
  std::vector<int> out(motions.size(), 0);
  std::string first_key, first_ref;
  int first_line = 0;
  for (size_t k = 0; k < motions.size(); ++k) {
    const postproc::Motion& mo = prog.motions[static_cast<size_t>(motions[k])];
    const std::string& file = prog.files[static_cast<size_t>(std::max(0, mo.file))].path;
    const std::string ref = mo.tool >= 0 ? prog.frames[static_cast<size_t>(mo.tool)].ref : "";
    // KRL's $TOOL without TOOL_DATA[n] (an inline frame, or none) selects no tool of a table
    const std::string key = ref.empty() || ref == "$TOOL" ? "" : programToolKey(ref);
    const std::string point = "path point " + std::to_string(k + 1);
    if (spec.mills.size() == 1) {
      if (key.empty()) continue;
      if (first_key.empty()) {
        first_key = key;
        first_ref = ref;
        first_line = mo.line;
      } else if (!sameToolKey(key, first_key)) {
        throw InputError(file, mo.line,
                         point + " is milled with tool " + ref + ", " + first_ref +
                             " before it (line " + std::to_string(first_line) +
                             "), but the cell has one mill, " + millLabel(spec.mills.front()) +
                             "; hint: list one <mill tool=\"...\"> per tool in the cell's "
                             "<process> (docs/process.md, tool table)");
      }
      continue;
    }
    if (key.empty()) {
      throw InputError(file, mo.line,
                       point + ": nothing selects a tool, and the cell's tool table has " +
                           std::to_string(spec.mills.size()) + " mills (" + millTable(spec) +
                           "): which mill cuts? Hint: select the tool before the path (KRL "
                           "$TOOL=TOOL_DATA[n]/BAS(#TOOL,n), RAPID tooldata, FANUC UTOOL_NUM)");
    }
    out[k] = millIndex(spec, key);
    if (out[k] < 0) {
      throw InputError(file, mo.line,
                       point + " is milled with tool " + ref +
                           ", which is not a mill of the cell's tool table (" + millTable(spec) +
                           "); hint: select a mill's tool before the milling path (a drill "
                           "cannot mill), or add <mill tool=\"" +
                           key + "\" .../> to the cell's <process>");
    }
  }
  return out;
}

/// The program's target edits of the compensated points [first, first + block.size()) (their
/// frames `frame`), and the failures and refusals among them, in path order.
void editMillingTargets(MillingCompensationResult& r, const std::vector<const Pose*>& frame,
                        std::size_t first, std::span<const PathPointCompensation> block) {
  postproc::Program& prog = *r.context.job.program;
  for (size_t k = 0; k < block.size(); ++k) {
    const size_t i = first + k;
    const postproc::Target& t = prog.targets()[static_cast<size_t>(r.targets[i])];
    const PathPointCompensation& p = block[k];
    if (!p.ok) {
      r.failures.push_back("path point " + std::to_string(i + 1) + " (" +
                           prog.files[static_cast<size_t>(t.file)].path + ":" +
                           std::to_string(t.line) + "): not compensated: " + p.reason);
      continue;
    }
    std::optional<postproc::Configuration> cfg;
    if (t.config.present()) cfg = postproc::parseConfigurationText(p.config_text);
    const postproc::EditResult er =
        postproc::replaceTargetPose(prog, r.targets[i], frame[i]->inverse() * p.T_programmed, cfg);
    if (!er.ok) r.refused.push_back("path point " + std::to_string(i + 1) + ": " + er.reason);
  }
}

/// Every run of points with one mill (r.mill) decided and compensated as a path of its own with
/// that mill's process and TCP model, seeded with the joints of the run before it; each block of
/// points edited in the program and kept in r.points_comp (no sink) or handed to `sink`.
/// `path` is emptied once the runs' cutting decisions are made.
void compensateMillRuns(MillingCompensationResult& r, std::vector<MillingPathPoint>& path,
                        const std::vector<const Pose*>& frame, const MillingPathOptions& options,
                        const MillingPointsSink& sink) {
  const PredictionModel& cell = r.context.model;
  // the stock (workobject frame) moves with the part
  const Pose T_W_stock = r.context.cell.part_registration
                             ? partMotion(r.context.cell) * r.context.cell.T_base_wobj
                             : r.context.cell.T_base_wobj;
  std::optional<Vec6> seed;
  const size_t n = path.size();
  for (size_t b = 0; b < n;) {
    size_t e = b;
    while (e < n && r.mill[e] == r.mill[b]) ++e;
    const size_t i = static_cast<size_t>(r.mill[b]);
    const PredictionModel& own =
        i < cell.drill_models.size() && cell.drill_models[i] ? *cell.drill_models[i] : cell;
    std::optional<PredictionModel> with;  // a copy only when the run's mill is not the first
    if (i > 0) {
      with = own;
      with->process.milling = cell.process.mills[i];
    }
    const PredictionModel& m = with ? *with : own;
    // one run (the usual path): the job's own vectors, no copies
    const bool whole = b == 0 && e == n;
    std::vector<MillingPathPoint> run_copy;
    std::vector<Pose> points_copy;
    if (!whole) {
      run_copy.assign(path.begin() + static_cast<std::ptrdiff_t>(b),
                      path.begin() + static_cast<std::ptrdiff_t>(e));
      points_copy.assign(r.points.begin() + static_cast<std::ptrdiff_t>(b),
                         r.points.begin() + static_cast<std::ptrdiff_t>(e));
    }
    std::vector<CuttingDecision> cutting =
        decideCutting(m.process.milling, T_W_stock, whole ? path : run_copy);
    // r.cutting holds the decisions of the points handed over (the exports read them)
    if (whole) {
      r.cutting = std::move(cutting);
      std::vector<MillingPathPoint>().swap(path);
    } else {
      r.cutting.insert(r.cutting.end(), cutting.begin(), cutting.end());
    }
    MillingPathOptions with_stock = options;
    with_stock.T_W_stock = T_W_stock;
    std::optional<Vec6> run_seed = seed;
    const auto each = [&](size_t first, std::span<PathPointCompensation> block) {
      for (const PathPointCompensation& p : block)
        if (p.ok) seed = p.theta_d;
      editMillingTargets(r, frame, b + first, block);
      if (sink) {
        r.points_comp.assign(std::make_move_iterator(block.begin()),
                             std::make_move_iterator(block.end()));
        r.first = b + first;
        sink(r);
        r.points_comp.clear();
      } else {
        r.points_comp.insert(r.points_comp.end(), std::make_move_iterator(block.begin()),
                             std::make_move_iterator(block.end()));
      }
    };
    compensateMillingPath(m, whole ? r.points : points_copy, whole ? &r.cutting : &cutting,
                          run_seed ? &*run_seed : nullptr, with_stock, each);
    b = e;
  }
  r.first = 0;
}

}  // namespace

const MillingSpec& millOf(const MillingCompensationResult& r, std::size_t i) {
  const ProcessSpec& spec = r.context.model.process;
  const size_t k = i < r.mill.size() ? static_cast<size_t>(r.mill[i]) : 0;
  return k < spec.mills.size() ? spec.mills[k] : spec.milling;
}

MillingCompensationResult compensateMillingJob(const std::string& cell_path,
                                               const std::string& program_path, bool force,
                                               const MillingPathOptions& options) {
  return compensateMillingJob(cell_path, program_path, force, options, nullptr);
}

MillingCompensationResult compensateMillingJob(const std::string& cell_path,
                                               const std::string& program_path, bool force,
                                               const MillingPathOptions& options,
                                               const MillingPointsSink& sink) {
  MillingCompensationResult r;
  r.context = loadPredictionContext(cell_path, program_path, std::nullopt, "", 0.5, false, 1);
  postproc::Program& prog = *r.context.job.program;
  if (const auto note = checkNotCompensated(prog, force)) r.context.job.notes.push_back(*note);
  postproc::markCompensated(prog, markerText(r.context.cell, "milling path"));
  prog.position_min_decimals = 5;
  std::vector<const Pose*> frame;  // T_W_frame per point (the program's frame or the cell's)
  std::vector<MillingPathPoint> path;
  std::vector<int> motions;  // the motion of each point
  std::vector<bool> seen(prog.targets().size(), false);
  for (const postproc::Motion& mo : prog.motions) {
    if (mo.type != postproc::MotionType::kLinear || mo.target < 0 || !mo.derivation.empty())
      continue;
    const postproc::Target& t = prog.targets()[static_cast<size_t>(mo.target)];
    if (t.kind != postproc::TargetKind::kCartesian || !postproc::targetComplete(t) ||
        seen[static_cast<size_t>(mo.target)]) {
      continue;
    }
    seen[static_cast<size_t>(mo.target)] = true;
    const postproc::Frame* base =
        mo.base >= 0 ? &prog.frames[static_cast<size_t>(mo.base)] : nullptr;
    const Pose* T_W_frame = base && base->resolved ? &base->pose : &r.context.cell.T_base_wobj;
    r.targets.push_back(mo.target);
    frame.push_back(T_W_frame);
    r.points.push_back(*T_W_frame * postproc::targetPose(prog, t));
    // on the part where the cell's <part_registration> found it, as a drilled hole is aimed
    if (r.context.cell.part_registration)
      r.points.back() = partMotion(r.context.cell) * r.points.back();
    path.push_back({r.points.back(), mo.speed_mm_s >= 0 ? mo.speed_mm_s * 1e-3 : -1.0});
    motions.push_back(static_cast<int>(&mo - prog.motions.data()));
  }
  if (r.points.empty()) {
    throw InputError(program_path, 0,
                     "no linear path points (LIN/MoveL/L to Cartesian targets) in the program");
  }
  r.mill = millsOfPath(r.context.model.process, prog, motions);
  std::vector<int>().swap(motions);
  compensateMillRuns(r, path, frame, options, sink);
  return r;
}

}  // namespace roprec::api
