#include "plugin/api/milling_job.hpp"

#include <algorithm>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <span>

#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "postproc/program.hpp"
#include "postproc/program_stream.hpp"
#include "postproc/streamed_edits.hpp"

namespace roprec::api {

bool cellIsMilling(const std::string& cell_path) {
  const CellSpec cell = loadCell(cell_path);
  return cell.has_process && cell.process.str("type") == "milling";
}

namespace {

/// The compensation marker's words (postproc::markCompensated, postproc::findCompensationMarker).
constexpr std::string_view kCompensatedMarker = "roprec compensated";

std::string millTable(const ProcessSpec& spec) {
  std::string t;
  for (const MillingSpec& m : spec.mills) t += (t.empty() ? "" : ", ") + millLabel(m);
  return t;
}

/// The mill of each path point, point after point in path order: the one its motion's active
/// tool selects (docs/process.md §8, tool table); 0 for a single mill, which mills with one tool.
class PathMills {
 public:
  explicit PathMills(const ProcessSpec& spec) : spec_(spec) {}
  /// The mill of path point `k` (0-based), the motion `mo` of `prog`. Throws InputError at a tool
  /// the cell's mills do not have, at no tool with several mills, and at a second tool with one.
  int operator()(const postproc::Program& prog, const postproc::Motion& mo, size_t k) {
    const std::string& file = prog.files[static_cast<size_t>(std::max(0, mo.file))].path;
    const std::string ref = mo.tool >= 0 ? prog.frames[static_cast<size_t>(mo.tool)].ref : "";
    // KRL's $TOOL without TOOL_DATA[n] (an inline frame, or none) selects no tool of a table
    const std::string key = ref.empty() || ref == "$TOOL" ? "" : programToolKey(ref);
    const std::string point = "path point " + std::to_string(k + 1);
    if (spec_.mills.size() == 1) {
      if (key.empty()) return 0;
      if (first_key_.empty()) {
        first_key_ = key;
        first_ref_ = ref;
        first_line_ = mo.line;
      } else if (!sameToolKey(key, first_key_)) {
        throw InputError(file, mo.line,
                         point + " is milled with tool " + ref + ", " + first_ref_ +
                             " before it (line " + std::to_string(first_line_) +
                             "), but the cell has one mill, " + millLabel(spec_.mills.front()) +
                             "; hint: list one <mill tool=\"...\"> per tool in the cell's "
                             "<process> (docs/process.md, tool table)");
      }
      return 0;
    }
    if (key.empty()) {
      throw InputError(file, mo.line,
                       point + ": nothing selects a tool, and the cell's tool table has " +
                           std::to_string(spec_.mills.size()) + " mills (" + millTable(spec_) +
                           "): which mill cuts? Hint: select the tool before the path (KRL "
                           "$TOOL=TOOL_DATA[n]/BAS(#TOOL,n), RAPID tooldata, FANUC UTOOL_NUM)");
    }
    const int m = millIndex(spec_, key);
    if (m < 0) {
      throw InputError(file, mo.line,
                       point + " is milled with tool " + ref +
                           ", which is not a mill of the cell's tool table (" + millTable(spec_) +
                           "); hint: select a mill's tool before the milling path (a drill "
                           "cannot mill), or add <mill tool=\"" +
                           key + "\" .../> to the cell's <process>");
    }
    return m;
  }

 private:
  const ProcessSpec& spec_;
  std::string first_key_, first_ref_;
  int first_line_{0};
};

/// The mill of every path point (the motions `motions` of `prog`; PathMills).
std::vector<int> millsOfPath(const ProcessSpec& spec, const postproc::Program& prog,
                             const std::vector<int>& motions) {
  std::vector<int> out(motions.size(), 0);
  PathMills mills(spec);
  for (size_t k = 0; k < motions.size(); ++k)
    out[k] = mills(prog, prog.motions[static_cast<size_t>(motions[k])], k);
  return out;
}

/// Whether motion `mo` of `prog` moves to a path point: a linear motion to a complete Cartesian
/// target (compensateMillingJob also skips a target an earlier path point has).
bool pathMotion(const postproc::Program& prog, const postproc::Motion& mo) {
  if (mo.type != postproc::MotionType::kLinear || mo.target < 0 || !mo.derivation.empty())
    return false;
  const postproc::Target& t = prog.targets()[static_cast<size_t>(mo.target)];
  return t.kind == postproc::TargetKind::kCartesian && postproc::targetComplete(t);
}

/// T_W_frame of a path motion's target: its program's base frame, or the cell's workobject.
const Pose& pathFrame(const PredictionContext& c, const postproc::Program& prog,
                      const postproc::Motion& mo) {
  const postproc::Frame* base = mo.base >= 0 ? &prog.frames[static_cast<size_t>(mo.base)] : nullptr;
  return base && base->resolved ? base->pose : c.cell.T_base_wobj;
}

/// The nominal path point of a path motion (base frame; on the part where the cell's
/// <part_registration> found it, as a drilled hole is aimed) and its programmed speed.
MillingPathPoint pathPointOf(const PredictionContext& c, const postproc::Program& prog,
                             const postproc::Motion& mo, const Pose& T_W_frame) {
  const postproc::Target& t = prog.targets()[static_cast<size_t>(mo.target)];
  Pose T = T_W_frame * postproc::targetPose(prog, t);
  if (c.cell.part_registration) T = partMotion(c.cell) * T;
  return {T, mo.speed_mm_s >= 0 ? mo.speed_mm_s * 1e-3 : -1.0};
}

/// The model of a run of points milled by mill `i`: the mill's own model (its TCP) with its
/// process; `with` holds a copy when the mill is not the first.
const PredictionModel& runModel(const PredictionModel& cell, size_t i,
                                std::optional<PredictionModel>& with) {
  const PredictionModel& own =
      i < cell.drill_models.size() && cell.drill_models[i] ? *cell.drill_models[i] : cell;
  with.reset();
  if (i > 0) {
    with = own;
    with->process.milling = cell.process.mills[i];
  }
  return with ? *with : own;
}

/// The stock's (workobject) frame in the base frame: it moves with the part.
Pose stockFrame(const CellSpec& cell) {
  return cell.part_registration ? partMotion(cell) * cell.T_base_wobj : cell.T_base_wobj;
}

/// Path point i (its target t, its result p): a failure is recorded; otherwise its target is
/// edited by `replace(configuration)` and a refused edit recorded, both in path order.
template <class Replace>
void editPathPoint(MillingCompensationResult& r, const postproc::Program& prog, std::size_t i,
                   const postproc::Target& t, const PathPointCompensation& p, Replace&& replace) {
  if (!p.ok) {
    r.failures.push_back("path point " + std::to_string(i + 1) + " (" +
                         prog.files[static_cast<size_t>(t.file)].path + ":" +
                         std::to_string(t.line) + "): not compensated: " + p.reason);
    return;
  }
  std::optional<postproc::Configuration> cfg;
  if (t.config.present()) cfg = postproc::parseConfigurationText(p.config_text);
  const postproc::EditResult er = replace(cfg);
  if (!er.ok) r.refused.push_back("path point " + std::to_string(i + 1) + ": " + er.reason);
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
    editPathPoint(r, prog, i, t, p, [&](const std::optional<postproc::Configuration>& cfg) {
      return postproc::replaceTargetPose(prog, r.targets[i], frame[i]->inverse() * p.T_programmed,
                                         cfg);
    });
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
  const Pose T_W_stock = stockFrame(r.context.cell);
  std::optional<Vec6> seed;
  const size_t n = path.size();
  for (size_t b = 0; b < n;) {
    size_t e = b;
    while (e < n && r.mill[e] == r.mill[b]) ++e;
    std::optional<PredictionModel> with;  // a copy only when the run's mill is not the first
    const PredictionModel& m = runModel(cell, static_cast<size_t>(r.mill[b]), with);
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
    std::vector<CuttingDecision>* run_cutting = &cutting;
    if (whole) {
      r.cutting = std::move(cutting);
      run_cutting = &r.cutting;
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
    compensateMillingPath(m, whole ? r.points : points_copy, run_cutting,
                          run_seed ? &*run_seed : nullptr, with_stock, each);
    b = e;
  }
  r.first = 0;
}

/// A path point of a program read by windows, held from its reading until its target is edited.
struct HeldPoint {
  size_t motion{0};  ///< in the stream's program
  int target{0};     ///< in the stream's program
  Pose T_W_frame{Pose::Identity()};
  MillingPathPoint path;
  int mill{0};
  std::optional<MillingEngagement> engagement;  ///< its cutting decision's (box stock)
};

/// The path points of a program read by windows (postproc::ProgramStream), one at a time in path
/// order: compensateMillingJob's (pathMotion, each target once) among the motions the reader
/// settled, each with its mill. The stream's motions and targets that neither the reader nor a
/// held point needs any more are retired before each window.
class StreamedPath {
 public:
  /// `named`: the first reading's MillingCompensationResult::named_lines (none in the first).
  StreamedPath(const PredictionContext& c, const std::string& path, size_t window_bytes,
               bool read_ahead, const std::vector<int>* named = nullptr)
      : c_(c),
        stream_(path, window_bytes > 0 ? window_bytes : postproc::ProgramStream::kWindowBytes,
                read_ahead, true),
        mills_(c.model.process),
        named_(named) {
    if (named_ != nullptr) named_read_.assign(named_->size(), 0);
  }
  postproc::ProgramStream& stream() { return stream_; }
  /// Appends the next path point to `held`; false at the end of the program. `on_window` is
  /// called after each window is read.
  bool next(std::deque<HeldPoint>& held, const std::function<void()>& on_window) {
    while (true) {
      if (started_ && nextOfWindow(held)) return true;
      if (ended_) return false;
      if (started_) retire(held);
      started_ = true;
      if (stream_.next()) {
        on_window();
      } else {
        ended_ = true;
      }
    }
  }
  /// Path points read so far.
  [[nodiscard]] size_t count() const { return count_; }
  /// The first path point's mill error (PathMills), none when every mill is known.
  [[nodiscard]] std::exception_ptr millError() const { return mill_error_; }
  /// The first line of the first file a later target edit can reach (INT_MAX: none): a held
  /// point's target, the motion looked at next (its target inline), or a target declared by name
  /// that a path point not read yet uses.
  [[nodiscard]] int firstEditableLine(const std::deque<HeldPoint>& held) const {
    const postproc::Program& p = stream_.program();
    int line = std::numeric_limits<int>::max();
    const auto inFirstFile = [&](int target) {
      if (target < 0) return;
      const postproc::Target& t = p.targets()[static_cast<size_t>(target)];
      if (t.file == 0) line = std::min(line, t.line);
    };
    for (const HeldPoint& h : held) inFirstFile(h.target);
    // a TP motion's position lies in /POS, after it: named_ (every TP position is named) holds
    // the lines of those path points use
    if (done_ < p.motions.size() && p.dialect != postproc::Dialect::kTp) {
      const postproc::Motion& mo = p.motions[done_];
      line = std::min(line, mo.line);
      if (mo.target >= 0 && p.targets()[static_cast<size_t>(mo.target)].name.empty())
        inFirstFile(mo.target);
    }
    if (named_ != nullptr && named_next_ < named_->size())
      line = std::min(line, (*named_)[named_next_]);
    return line;
  }

 private:
  bool nextOfWindow(std::deque<HeldPoint>& held) {
    const postproc::Program& p = stream_.program();
    const size_t settled = stream_.settledMotions();
    while (done_ < settled) {
      const size_t m = done_++;
      const postproc::Motion& mo = p.motions[m];
      if (!pathMotion(p, mo)) continue;
      if (seen_.size() < p.target_list.size()) seen_.resize(p.target_list.size(), 0);
      char& seen = seen_[static_cast<size_t>(mo.target)];
      if (seen != 0) continue;
      seen = 1;
      readNamed(p.targets()[static_cast<size_t>(mo.target)]);
      HeldPoint h;
      h.motion = m;
      h.target = mo.target;
      h.T_W_frame = pathFrame(c_, p, mo);
      h.path = pathPointOf(c_, p, mo, h.T_W_frame);
      // a point's mill error is kept: the whole-program job reads the program first
      if (!mill_error_) {
        try {
          h.mill = mills_(p, mo, count_);
        } catch (const InputError&) {
          mill_error_ = std::current_exception();
        }
      }
      ++count_;
      held.push_back(std::move(h));
      return true;
    }
    return false;
  }
  void retire(std::deque<HeldPoint>& held) {
    const postproc::Retired t = stream_.retire(held.empty() ? done_ : held.front().motion);
    const size_t dropped = t.target_end - t.target_begin;
    done_ -= t.motions;
    for (HeldPoint& h : held) {
      h.motion -= t.motions;
      if (static_cast<size_t>(h.target) >= t.target_end) h.target -= static_cast<int>(dropped);
    }
    if (dropped > 0 && t.target_begin < seen_.size()) {
      const auto b = seen_.begin() + static_cast<std::ptrdiff_t>(t.target_begin);
      seen_.erase(
          b, b + static_cast<std::ptrdiff_t>(std::min(dropped, seen_.size() - t.target_begin)));
    }
  }

  /// A path point's target declared by name in the first file: its entry of named_ read.
  void readNamed(const postproc::Target& t) {
    if (named_ == nullptr || t.name.empty() || t.file != 0) return;
    const std::vector<int>& lines = *named_;
    auto k =
        static_cast<size_t>(std::lower_bound(lines.begin(), lines.end(), t.line) - lines.begin());
    while (k < lines.size() && lines[k] == t.line && named_read_[k] != 0) ++k;
    if (k < lines.size() && lines[k] == t.line) named_read_[k] = 1;
    while (named_next_ < lines.size() && named_read_[named_next_] != 0) ++named_next_;
  }

  const PredictionContext& c_;
  postproc::ProgramStream stream_;
  PathMills mills_;
  const std::vector<int>* named_;  ///< lines of the named targets path points use
  std::vector<char> named_read_;   ///< per entry of named_: its path point was read
  size_t named_next_{0};           ///< the first entry not read
  std::vector<char> seen_;         ///< per target of the stream's program: a path point's
  size_t done_{0};                 ///< the stream's motions looked at
  size_t count_{0};
  std::exception_ptr mill_error_;
  bool started_{false};
  bool ended_{false};
};

/// The compensated points held[0, block.size()) of a program read by windows (path point `first`
/// is held[0]): what the exports read of them into r.block, and their failures in path order;
/// with `edits`, their target edits as editMillingTargets makes them and the refused ones.
void editStreamedTargets(MillingCompensationResult& r, const postproc::Program& prog,
                         postproc::StreamedEdits* edits, const std::deque<HeldPoint>& held,
                         std::size_t first, std::span<const PathPointCompensation> block) {
  r.block.clear();
  for (size_t k = 0; k < block.size(); ++k) {
    const size_t i = first + k;
    const HeldPoint& h = held[k];
    const postproc::Target& t = prog.targets()[static_cast<size_t>(h.target)];
    r.block.push_back({t.name, t.line, h.path.T_W_tcp, h.engagement, h.mill});
    const PathPointCompensation& p = block[k];
    editPathPoint(r, prog, i, t, p, [&](const std::optional<postproc::Configuration>& cfg) {
      if (edits == nullptr) return postproc::EditResult{true, ""};
      return edits->replaceTargetPose(h.target, h.T_W_frame.inverse() * p.T_programmed, cfg);
    });
  }
}

/// The path points of a job loadStreamedMillingJob loaded, read again by `path` and handed to the
/// chains run by run, block by block (compensateStreamedMillingJob); `edits` (none: the program
/// is not written) receives the target edits and writes the bytes no later edit can change.
void streamMillRuns(MillingCompensationResult& r, const MillingPathOptions& options,
                    StreamedPath& path, postproc::StreamedEdits* edits,
                    const MillingPointsSink& sink) {
  const PredictionModel& cell = r.context.model;
  const postproc::Program& prog = path.stream().program();
  std::deque<HeldPoint> held;  // read, not edited yet
  const auto on_window = [&] {
    if (edits == nullptr) return;
    edits->installed();
    edits->flushBeforeLine(path.firstEditableLine(held));
  };
  size_t given = 0;  // held[given ..] not handed to the chains yet
  MillingPathOptions with_stock = options;
  with_stock.T_W_stock = stockFrame(r.context.cell);
  std::optional<Vec6> seed;
  for (size_t run = 0; run < r.runs.size(); ++run) {
    const size_t begin = r.runs[run].first;
    const size_t end = run + 1 < r.runs.size() ? r.runs[run + 1].first : r.streamed_points;
    std::optional<PredictionModel> with;
    const PredictionModel& m = runModel(cell, static_cast<size_t>(r.runs[run].second), with);
    CuttingDecider decide(m.process.milling, with_stock.T_W_stock);
    size_t left = end - begin;
    const MillingPathSource source = [&](size_t count, std::vector<Pose>& points,
                                         std::vector<CuttingDecision>& cutting) {
      size_t n = 0;
      for (; n < count && left > 0; ++n, --left) {
        if (given == held.size() && !path.next(held, on_window))
          throw InternalError("the program has fewer path points than its first reading");
        HeldPoint& h = held[given++];
        points.push_back(h.path.T_W_tcp);
        cutting.push_back(decide(h.path));
        h.engagement = cutting.back().engagement;
      }
      return n;
    };
    std::optional<Vec6> run_seed = seed;
    const MillingPathSink each = [&](size_t first, std::span<PathPointCompensation> block) {
      for (const PathPointCompensation& p : block)
        if (p.ok) seed = p.theta_d;
      editStreamedTargets(r, prog, edits, held, begin + first, block);
      r.points_comp.assign(std::make_move_iterator(block.begin()),
                           std::make_move_iterator(block.end()));
      r.first = begin + first;
      if (sink) sink(r);
      r.points_comp.clear();
      held.erase(held.begin(), held.begin() + static_cast<std::ptrdiff_t>(block.size()));
      given -= block.size();
      if (edits != nullptr) edits->flushBeforeLine(path.firstEditableLine(held));
    };
    compensateMillingPath(m, source, true, run_seed ? &*run_seed : nullptr, with_stock, each);
  }
  r.first = 0;
  r.block.clear();
  if (path.next(held, on_window) || path.millError())
    throw InternalError("the program's path points are not those of its first reading");
}

}  // namespace

const std::string& MillingCompensationResult::targetName(std::size_t i) const {
  if (streamed) return block[i - first].target;
  return context.job.program->targets()[static_cast<size_t>(targets[i])].name;
}

int MillingCompensationResult::targetLine(std::size_t i) const {
  if (streamed) return block[i - first].line;
  return context.job.program->targets()[static_cast<size_t>(targets[i])].line;
}

const Pose& MillingCompensationResult::nominal(std::size_t i) const {
  return streamed ? block[i - first].nominal : points[i];
}

const std::optional<MillingEngagement>& MillingCompensationResult::engagement(std::size_t i) const {
  return streamed ? block[i - first].engagement : cutting[i].engagement;
}

const MillingSpec& millOf(const MillingCompensationResult& r, std::size_t i) {
  const ProcessSpec& spec = r.context.model.process;
  const size_t k = r.streamed          ? static_cast<size_t>(r.block[i - r.first].mill)
                   : i < r.mill.size() ? static_cast<size_t>(r.mill[i])
                                       : 0;
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
    if (!pathMotion(prog, mo) || seen[static_cast<size_t>(mo.target)]) continue;
    seen[static_cast<size_t>(mo.target)] = true;
    const Pose* T_W_frame = &pathFrame(r.context, prog, mo);
    r.targets.push_back(mo.target);
    frame.push_back(T_W_frame);
    path.push_back(pathPointOf(r.context, prog, mo, *T_W_frame));
    r.points.push_back(path.back().T_W_tcp);
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

namespace {

/// Whether `program_path` is an ABB RAPID module or a FANUC TP program ProgramStream reads by
/// windows.
bool windowedModuleStreams(const std::string& program_path) {
  try {
    postproc::ProgramStream s(program_path, postproc::ProgramStream::kWindowBytes, false, true);
    const postproc::Dialect d = s.program().dialect;
    return s.windowed() && (d == postproc::Dialect::kRapid || d == postproc::Dialect::kTp);
  } catch (const InputError&) {
    return false;  // the whole-program path gives the error
  }
}

}  // namespace

bool millingStreams(const std::string& program_path) { return millingStreams(program_path, false); }

bool millingStreams(const std::string& program_path, bool force) {
  if (compensationStreams(program_path, CompensationJob{}, force)) return true;
  // a marked module without --force takes the whole-program path, which names the marker's line
  return windowedModuleStreams(program_path) && (force || !fileHoldsMarker(program_path));
}

bool millingPathStreams(const std::string& program_path) {
  return millingStreams(program_path) || windowedModuleStreams(program_path);
}

MillingCompensationResult loadStreamedMillingJob(const std::string& cell_path,
                                                 const std::string& program_path,
                                                 std::size_t window_bytes, bool force) {
  MillingCompensationResult r;
  r.streamed = true;
  r.context = loadPredictionContext(cell_path, "", std::nullopt, "", 0.5, false, 1);
  r.context.job.path = program_path;
  StreamedPath path(r.context, program_path, window_bytes, false);
  // the first file's window that holds the compensation marker (checkNotCompensated)
  std::optional<postproc::SourceFile> marked;
  const auto on_window = [&] {
    const postproc::SourceFile& f = path.stream().program().files[0];
    if (marked || f.bytes.find(kCompensatedMarker) == std::string::npos) return;
    marked.emplace();
    marked->path = f.path;
    marked->bytes = f.bytes;
    marked->line_starts = f.line_starts;
    marked->line_base = f.line_base;
  };
  std::deque<HeldPoint> held;
  while (path.next(held, on_window)) {
    const HeldPoint& h = held.back();
    if (r.runs.empty() || r.runs.back().second != h.mill)
      r.runs.emplace_back(path.count() - 1, h.mill);
    const postproc::Target& t = path.stream().program().targets()[static_cast<size_t>(h.target)];
    if (!t.name.empty() && t.file == 0) r.named_lines.push_back(t.line);
    held.clear();
  }
  std::sort(r.named_lines.begin(), r.named_lines.end());
  r.context.job.program = std::move(path.stream().program());
  // the files, frames and notes stay; the second reading has the motions and targets again
  std::vector<postproc::Motion>().swap(r.context.job.program->motions);
  std::vector<postproc::Target>().swap(r.context.job.program->target_list);
  std::vector<postproc::TextId>().swap(r.context.job.program->marker_texts);
  // the marker where the whole program has it first (its first file's window, else the .dat):
  // refused, or noted with `force`, before the path's errors as compensateMillingJob does
  std::optional<std::string> note;
  if (marked) {
    postproc::Program scratch;
    scratch.files.push_back(std::move(*marked));
    note = checkNotCompensated(scratch, force);
  } else {
    note = checkNotCompensated(*r.context.job.program, force);
  }
  if (note) r.context.job.notes.push_back(*note);
  if (path.millError()) std::rethrow_exception(path.millError());
  r.streamed_points = path.count();
  if (r.streamed_points == 0) {
    throw InputError(program_path, 0,
                     "no linear path points (LIN/MoveL/L to Cartesian targets) in the program");
  }
  return r;
}

void compensateStreamedMillingJob(MillingCompensationResult& r, const MillingPathOptions& options,
                                  const ByteWriter& write_src, std::optional<std::string>& dat,
                                  const MillingPointsSink& sink, std::size_t window_bytes) {
  if (!r.streamed || !r.context.job.program)
    throw InternalError("compensateStreamedMillingJob: the job was not loaded by windows");
  StreamedPath path(r.context, r.context.job.path, window_bytes, options.threads > 1,
                    &r.named_lines);
  postproc::Program& prog = path.stream().program();
  prog.position_min_decimals = 5;
  prog.fanuc_turn_axes = r.context.job.program->fanuc_turn_axes;
  postproc::StreamedEdits edits(path.stream(), write_src,
                                markerText(r.context.cell, "milling path"),
                                r.context.job.program->files[0]);
  streamMillRuns(r, options, path, &edits, sink);
  if (!r.failures.empty() || !r.refused.empty()) return;  // nothing is written
  edits.finish();
  dat = edits.dat();
}

void computeStreamedMillingPath(MillingCompensationResult& r, const MillingPathOptions& options,
                                const MillingPointsSink& sink, std::size_t window_bytes) {
  if (!r.streamed || !r.context.job.program)
    throw InternalError("computeStreamedMillingPath: the job was not loaded by windows");
  StreamedPath path(r.context, r.context.job.path, window_bytes, options.threads > 1,
                    &r.named_lines);
  streamMillRuns(r, options, path, nullptr, sink);
}

}  // namespace roprec::api
