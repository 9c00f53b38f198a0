#include "plugin/api/job.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <limits>
#include <system_error>
#include <thread>

#include "compensator/precision/parallel.hpp"
#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "postproc/drill.hpp"
#include "postproc/program_stream.hpp"
#include "postproc/streamed_edits.hpp"

namespace roprec::api {

const char* version() { return ROPREC_VERSION_STRING; }

int resolvedThreads(int threads) {
  if (threads < 0) throw UsageError("--threads must be 0 (every core) or a positive count");
  if (threads == 0) return static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  return threads;
}

int PredictionResult::failed() const {
  return static_cast<int>(std::count_if(holes.begin(), holes.end(), [](const HolePrediction& h) {
    return h.status != HoleStatus::kOk;
  }));
}

namespace {

std::string mm(double v_m) { return formatNumber(v_m * 1e3, 3); }

std::string poseText(const Pose& T) {
  const Vec3 t = T.translation();
  const double ang = Eigen::AngleAxisd(T.linear()).angle() / kDeg;
  return "xyz " + mm(t.x()) + " " + mm(t.y()) + " " + mm(t.z()) + " mm, rotated " +
         formatNumber(ang, 3) + " deg";
}

bool sameIequal(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  }
  return true;
}

std::optional<Pose> givenFrame(const JobOptions& o, const std::string& ref) {
  for (const FrameDefinition& f : o.frames) {
    if (sameIequal(f.ref, ref)) return f.pose;
  }
  return std::nullopt;
}

/// Rebuilds the prediction model with the program's TCP (--tool program); the cell's tool mass,
/// centre of mass and inertia are kept.
void useProgramTool(PredictionContext& c, const Pose& T_flange_tcp) {
  c.tool.T_flange_tcp = T_flange_tcp;
  c.cell.tool.T_flange_tcp = T_flange_tcp;
  PredictionSetup s;
  s.robot = c.robot;
  s.tool = c.tool;
  s.process = c.process;
  s.uncertainty = c.model.uncertainty;
  s.accuracy = c.model.accuracy;
  s.capability = c.model.capability;
  const ControllerGravity cg = controllerGravityOf(c.robot.card, &c.cell, c.tool);
  s.controller_gravity = cg.gravity_compensated;
  s.calibration_load = cg.calibration_load;
  s.default_tolerance = c.model.default_tolerance;
  s.drill_tools = drillToolsOf(c.cell, c.robot.card);
  for (const HoleRequest& r : c.job.requests) {
    if (r.diameter > 0) s.hole_diameters.push_back(r.diameter);
    if (r.drill > 0 || r.feed > 0 || r.spindle_rpm > 0)
      s.hole_processes.push_back(holeProcessOf(r));
  }
  const ConfigurationOptions cfg = c.model.config_options;
  c.model = buildPredictionModel(s);
  c.model.config_options = cfg;
}

/// The cell's TCP of the program tool `ref`: the <tcp> of the tool-table drill it selects, else
/// the cell's <tool>.
const ToolSpec& toolOfProgramTool(const PredictionContext& c, const std::string& ref) {
  if (!c.process || c.process->type != ProcessType::kDrilling) return c.cell.tool;
  // a single drill drills every hole, whatever the program's tool
  const int i = c.process->drills.size() == 1 ? 0 : drillIndex(*c.process, programToolKey(ref));
  if (i < 0 || static_cast<size_t>(i) >= c.cell.drill_tools.size()) return c.cell.tool;
  const std::optional<ToolSpec>& own = c.cell.drill_tools[static_cast<size_t>(i)];
  return own ? *own : c.cell.tool;
}

/// The notes a frame and tool resolution writes (each resolution stated once, by key) and where
/// a hole's frame or tool is written.
class ResolutionNotes {
 public:
  ResolutionNotes(const postproc::Program& p, std::vector<std::string>& notes)
      : program_(p), notes_(notes) {}

  void state(const std::string& key, const std::string& text) {
    if (std::find(stated_.begin(), stated_.end(), key) != stated_.end()) return;
    stated_.push_back(key);
    notes_.push_back(kResolutionPrefix + text);
  }

  /// The file and line of a frame (`file`, `line`), else of the hole's bottom motion.
  [[nodiscard]] std::pair<std::string, int> where(int file, int line, const HoleFrameUse& h) const {
    if (line > 0 && file >= 0) return {program_.files[static_cast<size_t>(file)].path, line};
    return {program_.files[static_cast<size_t>(std::max(0, h.file))].path, h.line};
  }

 private:
  const postproc::Program& program_;
  std::vector<std::string>& notes_;
  std::vector<std::string> stated_;
};

/// Base frames only the controller defines, decided per program frame in hole order (the first
/// hole in a frame no one defines is the one an error names), then applied to the holes set up so
/// far (a deferred job's holes get theirs when they are set up: setUpHoles).
void resolveBaseFrames(PredictionContext& c, const JobOptions& o, ResolutionNotes& notes) {
  const postproc::Program& p = *c.job.program;
  bool base_explicit = false;
  c.job.base_frames.assign(p.frames.size(), std::nullopt);
  for (const HoleFrameUse& h : c.job.frame_uses) {
    if (h.base < 0) continue;  // no frame named: the cell's workobject (noted by hole_input)
    const postproc::Frame& f = p.frames[static_cast<size_t>(h.base)];
    if (f.resolved || c.job.base_frames[static_cast<size_t>(h.base)]) continue;
    std::optional<Pose> T = givenFrame(o, f.ref);
    std::string how = "--frame '" + f.ref + "=...'";
    if (!T && o.frame_pose) {
      T = *o.frame_pose;
      how = "--frame";
    }
    if (!T && o.frame_cell) {
      T = c.cell.T_base_wobj;
      how = "the cell's <workobject> (--frame cell)";
    }
    if (!T) {
      const auto [file, line] = notes.where(-1, 0, h);
      throw InputError(file, line,
                       "hole " + h.id + " uses the base frame " + f.ref +
                           ", which only the controller defines (not the program, the cell or "
                           "--frame). Give --frame \"x y z a b c\" (its pose in the robot base "
                           "frame, mm and deg, KUKA A-B-C) or --frame cell (the cell's "
                           "<workobject> is that frame)");
    }
    c.job.base_frames[static_cast<size_t>(h.base)] = *T;
    base_explicit = true;
    notes.state("base " + f.ref, "base frame " + f.ref + " (defined only on the controller) = " +
                                     how + ": " + poseText(*T));
  }
  for (size_t i = 0; i < c.job.sources.size(); ++i)
    applyBaseFrame(c.job, c.job.requests[i], c.job.sources[i]);
  if (base_explicit) {
    c.job.notes.erase(
        std::remove_if(c.job.notes.begin(), c.job.notes.end(),
                       [](const std::string& n) { return n.rfind("program base frame ", 0) == 0; }),
        c.job.notes.end());
  }
}

/// A program tool's TCP that `--tool program` takes, with the text of how it differs.
struct ProgramTcp {
  Pose T;
  std::string difference;
};

/// One program tool (of hole `h`) against the TCP of the drill it selects (its own <tcp>, else the
/// cell's <tool>): a resolution the options give is stated; a difference they do not resolve is
/// an error at the tool's line. Returns the program's TCP when `--tool program` takes it.
std::optional<ProgramTcp> checkProgramTool(PredictionContext& c, const JobOptions& o,
                                           const HoleFrameUse& h, ResolutionNotes& notes) {
  const postproc::Program& p = *c.job.program;
  const postproc::Frame& tf = p.frames[static_cast<size_t>(h.tool)];
  const ToolSpec& reference = toolOfProgramTool(c, tf.ref);
  const bool own_tcp = &reference != &c.cell.tool;
  const Pose& T_cell = reference.T_flange_tcp;
  const std::string cell_tool =
      own_tcp ? "drill " + reference.name + " <tcp>"
              : "'" + (c.cell.tool.name.empty() ? "tool" : c.cell.tool.name) + "'";
  std::optional<Pose> Tt = tf.resolved ? std::optional<Pose>(tf.pose) : givenFrame(o, tf.ref);
  const auto [file, line] = notes.where(tf.file, tf.line, h);
  if (!Tt && own_tcp) {
    notes.state("tool " + tf.ref, "tool " + tf.ref +
                                      " (defined only on the controller) = the cell's " +
                                      cell_tool + ": TCP " + poseText(T_cell));
    return std::nullopt;
  }
  if (!Tt) {
    if (o.tool == "cell") {
      notes.state("tool " + tf.ref, "tool " + tf.ref +
                                        " (defined only on the controller) = the cell's tool " +
                                        cell_tool + " (--tool cell): TCP " + poseText(T_cell));
      return std::nullopt;
    }
    throw InputError(h.file >= 0 ? p.files[static_cast<size_t>(h.file)].path : file, h.line,
                     "hole " + h.id + " uses the tool " + tf.ref +
                         ", which only the controller defines. Give --tool cell (the cell's "
                         "tool " +
                         cell_tool + " is that tool) or --frame '" + tf.ref +
                         "=x y z a b c' (its TCP in the flange frame, mm and deg)");
  }
  const double dt = (Tt->translation() - T_cell.translation()).norm();
  const double dr = Eigen::AngleAxisd(Tt->linear().transpose() * T_cell.linear()).angle();
  if (dt <= 1e-5 && dr <= 1e-4) return std::nullopt;  // 0.01 mm, 0.006 deg: the same tool
  const std::string diff = "the program's tool " + tf.ref + " (TCP " + poseText(*Tt) +
                           ") differs from the cell's " + (own_tcp ? "" : "tool ") + cell_tool +
                           " (TCP " + poseText(T_cell) + ") by " + mm(dt) + " mm and " +
                           formatNumber(dr / kDeg, 3) + " deg";
  if (o.tool == "cell") {
    notes.state("tool " + tf.ref, diff +
                                      ": --tool cell: the cell's TCP is used; the program's "
                                      "targets are taken as TCP poses of the cell's tool");
    return std::nullopt;
  }
  if (o.tool == "program" && own_tcp) {
    throw InputError(file, line,
                     diff +
                         "; --tool program takes one TCP for the cell's <tool>, not for a drill "
                         "with a <tcp> of its own: correct the drill's <tcp> in " +
                         c.cell.file + " or the program's tool, or give --tool cell");
  }
  if (o.tool == "program") return ProgramTcp{*Tt, diff};
  if (own_tcp) {
    throw InputError(file, line,
                     diff + ". Correct the drill's <tcp> in " + c.cell.file +
                         " or the program's tool, or give --tool cell (the cell's TCP is the "
                         "real one)");
  }
  throw InputError(file, line,
                   diff +
                       ". Give --tool program (the program's TCP is the real one) or --tool "
                       "cell (the cell's TCP is the real one)");
}

/// Every program tool checked (checkProgramTool); with `--tool program` the program's one TCP
/// replaces the cell's (a program with two is a usage error).
void resolveProgramTools(PredictionContext& c, const JobOptions& o, ResolutionNotes& notes) {
  std::optional<std::pair<std::string, Pose>> program_tool;
  for (const HoleFrameUse& h : c.job.frame_uses) {
    if (h.tool < 0) continue;  // the program names no tool
    const std::optional<ProgramTcp> tcp = checkProgramTool(c, o, h, notes);
    if (!tcp) continue;
    const std::string& ref = c.job.program->frames[static_cast<size_t>(h.tool)].ref;
    if (program_tool && !program_tool->second.isApprox(tcp->T, 1e-9)) {
      throw UsageError("--tool program: the program drills with more than one tool (" +
                       program_tool->first + ", " + ref +
                       "); the model takes one tool per job: give --tool cell or split the "
                       "program");
    }
    program_tool = std::make_pair(ref, tcp->T);
    notes.state("tool " + ref, tcp->difference +
                                   ": --tool program: the program's TCP is used (mass data "
                                   "from the cell)");
  }
  if (program_tool) useProgramTool(c, program_tool->second);
}

/// Program frames and tool against the cell (docs/programs.md §15): a base frame or tool that
/// only the controller defines, or a program tool that differs from the cell's, is an error
/// unless the options say how to resolve it; every resolution is stated in the job's notes.
void resolveFramesAndTool(PredictionContext& c, const JobOptions& o) {
  if (o.frame_cell && c.cell.root.child("workobject") == nullptr) {
    throw InputError(c.cell.file, std::max(1, c.cell.root.line),
                     "--frame cell: the cell has no <workobject>, so it defines no frame (the "
                     "robot base frame would be used silently). Add <workobject xyz=\"...\" "
                     "rpy=\"...\"/> to the cell, or give --frame \"x y z a b c\"");
  }
  if (!c.job.program || c.job.is_hole_list) return;
  ResolutionNotes notes(*c.job.program, c.job.notes);
  resolveBaseFrames(c, o, notes);
  resolveProgramTools(c, o, notes);
}

PredictionContext loadContext(const std::string& cell_path, const std::string& program_path,
                              const JobOptions& o, bool load_holes = true, bool defer_setup = false,
                              bool keep_requests = false) {
  if (!o.tool.empty() && o.tool != "program" && o.tool != "cell")
    throw UsageError("--tool must be program or cell");
  PredictionContext c =
      loadPredictionContext(cell_path, program_path, o.holes, o.uncertainty, o.match_tol_mm,
                            load_holes, resolvedThreads(o.threads), defer_setup, keep_requests);
  if (o.fanuc_turn_axes) {
    c.model.config_options.fanuc_turn_axes = *o.fanuc_turn_axes;
    if (c.job.program) c.job.program->fanuc_turn_axes = *o.fanuc_turn_axes;
  }
  if (load_holes) resolveFramesAndTool(c, o);
  return c;
}

double perpNorm(const Vec3& v, const Vec3& a) { return (v - v.dot(a) * a).norm(); }

/// Holes moved with the part by G = partMotion (base frame): every pose and point of each request.
void moveWithPart(const Pose& G, std::span<HoleRequest> holes) {
  for (HoleRequest& h : holes) {
    h.T_W_tcp = G * h.T_W_tcp;
    if (h.surface_W) h.surface_W = G * *h.surface_W;
    if (h.nominal_axis)
      h.nominal_axis = std::make_pair(Vec3(G * h.nominal_axis->first),
                                      Vec3(G.linear() * h.nominal_axis->second));
  }
}

/// The job's holes where the cell's <part_registration> found the part: every pose and point of
/// a request moved by G = partMotion (base frame), whatever frame its program uses.
std::vector<HoleRequest> registeredHoles(const PredictionContext& c) {
  std::vector<HoleRequest> out = c.job.requests;
  moveWithPart(partMotion(c.cell), out);
  return out;
}

/// compensateHoles over the job's holes (`req`), aimed at the registered part when the cell has
/// one, each finished block handed to `each`; the statistics into r.stats.
void compensateJobHolesInBlocks(CompensationResult& r, const std::vector<HoleRequest>& req,
                                const CompensationOptions& options, const CompensationSink& each) {
  if (r.context.cell.part_registration) {
    const std::vector<HoleRequest> aimed = registeredHoles(r.context);
    compensateHoles(r.context.model, aimed, options, each, &r.stats);
  } else {
    compensateHoles(r.context.model, req, options, each, &r.stats);
  }
}

/// Does a prediction job aim its holes at the registered part (JobOptions::registered_part)?
bool aimsAtRegisteredPart(const PredictionContext& c, const JobOptions& o) {
  return o.registered_part && c.cell.part_registration.has_value();
}

// ---- compensation stages after compensateHoles

/// A hole's compensated target: its world pose T_new = ΔT · (G ·) T · Rz(ψ) (with a part
/// registration the target first moves with the part, G, then compensates) and the configuration
/// to write (none: the program's own flag bytes stay unless the compensated target needs others).
struct CompensatedTarget {
  Pose T_W;
  std::optional<postproc::Configuration> config;
};

CompensatedTarget compensatedTarget(const CellSpec& cell, const HoleCompensation& h,
                                    const Pose& T_W_frame, const postproc::Program& prog,
                                    const postproc::Target& tg) {
  const Pose T_W_t = T_W_frame * postproc::targetPose(prog, tg);
  CompensatedTarget out;
  out.T_W = (cell.part_registration ? h.delta * partMotion(cell) * T_W_t : h.delta * T_W_t) *
            Pose(Eigen::AngleAxisd(h.psi, Vec3::UnitZ()));
  if (tg.config.present() && h.config_changed)
    out.config = postproc::parseConfigurationText(h.config_text);
  return out;
}

/// The edits of hole i's targets (T_new = ΔT · T · Rz(ψ)) queued into `log`, its refusals
/// appended to `refused`. Writes only the hole's own targets.
void editHoleTargets(CompensationResult& r, const HoleCompensation& h, size_t i,
                     postproc::EditLog& log, std::vector<std::string>& refused) {
  postproc::Program& prog = *r.context.job.program;
  const HoleSource& src = r.context.job.sources[i];
  for (const int t : src.targets) {
    const postproc::Target& tg = prog.targets()[static_cast<size_t>(t)];
    const CompensatedTarget ct = compensatedTarget(r.context.cell, h, src.T_W_frame, prog, tg);
    const postproc::EditResult er =
        postproc::replaceTargetPose(prog, t, src.T_W_frame.inverse() * ct.T_W, ct.config, log);
    if (!er.ok) {
      refused.push_back("hole " + h.id + " target " +
                        (tg.name.empty() ? std::to_string(t) : tg.name) + ": " + er.reason);
    }
  }
}

/// Every target of a drill cycle moves with its drill point. Block by block, the edits of the
/// holes whose targets are their own are prepared on `threads` workers (number formatting is
/// most of the work) while the block before is queued on a task of its own: there, in hole
/// order, the holes that share a target with another hole are edited (each reads what the one
/// before wrote) and every hole's edits and refusals are queued. The program's bytes and the
/// refusals are those of one thread.
std::vector<std::string> editProgram(CompensationResult& r, int threads) {
  constexpr size_t kBlock = 2048;  // holes whose edits are held at once (two blocks)
  postproc::Program& prog = *r.context.job.program;
  prog.position_min_decimals = 5;  // 0.01 µm: the written target carries the compensation
  const size_t n = r.holes.size();
  std::vector<char> edited(n);
  for (size_t i = 0; i < n; ++i) edited[i] = r.holes[i].ok ? 1 : 0;
  const std::vector<char> shared =
      holesSharingTargets(r.context.job.sources, edited, prog.targets().size());
  // block k's edits are held in blocks[k % 2]: prepared while block k - 1 is queued
  struct Block {
    std::vector<postproc::EditLog> logs = std::vector<postproc::EditLog>(kBlock);
    std::vector<std::vector<std::string>> refusals = std::vector<std::vector<std::string>>(kBlock);
  };
  std::array<Block, 2> blocks;
  auto blockOf = [&](size_t i) -> Block& { return blocks[(i / kBlock) % 2]; };
  std::vector<std::string> refused;
  pipelinedFor(
      n, kBlock, threads,
      [&](int, size_t i) {
        Block& blk = blockOf(i);
        const size_t k = i % kBlock;
        blk.logs[k].ops.clear();
        blk.refusals[k].clear();
        if (edited[i] && !shared[i])
          editHoleTargets(r, r.holes[i], i, blk.logs[k], blk.refusals[k]);
      },
      [&](size_t b, size_t e) {
        Block& blk = blockOf(b);
        for (size_t i = b; i < e; ++i) {
          if (!edited[i]) continue;
          const size_t k = i - b;
          if (shared[i]) editHoleTargets(r, r.holes[i], i, blk.logs[k], blk.refusals[k]);
          postproc::applyEdits(prog, std::move(blk.logs[k]));
          for (std::string& x : blk.refusals[k]) refused.push_back(std::move(x));
        }
      });
  return refused;
}

bool wristJump(const Vec6& a, const Vec6& b, double threshold) {
  return std::abs(a[3] - b[3]) > threshold || std::abs(a[5] - b[5]) > threshold;
}

}  // namespace

/// The marker line written into every compensated program.
std::string markerText(const CellSpec& cell, const std::string& mode) {
  std::string name = cell.name.empty() ? std::string("(unnamed)") : cell.name;
  const std::string file = std::filesystem::path(cell.file).filename().string();
  return "cell " + name + " (" + file + "), roprec " + std::string(ROPREC_VERSION_STRING) + ", " +
         mode + "; do not compensate again";
}

namespace {

bool sameFile(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code e1;
  std::error_code e2;
  if (fs::exists(a, e1) && fs::exists(b, e2)) {
    std::error_code e;
    const bool eq = fs::equivalent(a, b, e);
    if (!e) return eq;
  }
  std::error_code e;
  const fs::path ca = fs::weakly_canonical(a, e);
  const fs::path cb = fs::weakly_canonical(b, e);
  return !e && ca == cb;
}

/// What compensationStats carries from a hole to the next: the hole before.
struct StatsCarry {
  bool any{false};
  bool ok{false};
  Vec6 theta_cmd{Vec6::Zero()};
  Vec6 joints{Vec6::Zero()};
};

/// Hole i (h) added to the before/after statistics.
void addHoleStats(CompensationResult::Stats& s, StatsCarry& prev,
                  const std::vector<HoleRequest>& req, size_t i, const HoleCompensation& h,
                  double jump_threshold) {
  if (h.before.status == HoleStatus::kOk)
    s.error_before_um.push_back(h.before.position_error * 1e6);
  if (h.before.verdict == Verdict::kConforms) ++s.conform_before;
  if (h.ok) {
    s.residual_after_um.push_back(perpNorm(h.residual, h.T_nominal.linear().col(2)) * 1e6);
    if (h.after.verdict == Verdict::kConforms) ++s.conform_after;
  }
  const bool same_face = i > 0 && req[i].T_W_tcp.linear().col(2).dot(
                                      req[i - 1].T_W_tcp.linear().col(2)) > std::cos(10.0 * kDeg);
  if (prev.any && h.ok && prev.ok && same_face) {
    s.jumps_after += wristJump(h.theta_cmd, prev.theta_cmd, jump_threshold) ? 1 : 0;
    s.jumps_before += wristJump(h.before.joints, prev.joints, jump_threshold) ? 1 : 0;
  }
  prev.any = true;
  prev.ok = h.ok;
  prev.theta_cmd = h.theta_cmd;
  prev.joints = h.before.joints;
}

/// Before/after statistics: errors ⊥ axis, conforming holes, axis-4/6 jumps within a face.
CompensationResult::Stats compensationStats(const CompensationResult& r, double jump_threshold) {
  CompensationResult::Stats s;
  StatsCarry prev;
  for (size_t i = 0; i < r.holes.size(); ++i)
    addHoleStats(s, prev, r.context.job.requests, i, r.holes[i], jump_threshold);
  return s;
}

/// Whether the compensated program may be written (CompensationResult::writable), given `failed`
/// of `n` holes not compensated and the edits refused.
void settleWritable(CompensationResult& r, const CompensationJob& job, size_t n) {
  r.writable = true;
  if (r.failed && !job.allow_partial) {
    r.writable = false;
    r.why_not_writable =
        std::to_string(r.failed) + " of " + std::to_string(n) +
        " holes could not be compensated; nothing written (use --allow-partial to keep their "
        "original targets)";
  } else if (!r.refused.empty() && !job.allow_partial) {
    r.writable = false;
    r.why_not_writable =
        "the writer refused " + std::to_string(r.refused.size()) + " target edits; nothing written";
  }
}

}  // namespace

namespace {

/// Holes predicted per block of the streaming predict (bounded memory, whatever the job's size).
constexpr size_t kPredictBlock = 2048;
/// The smallest block: the last blocks halve down to it.
constexpr size_t kLastBlock = 256;

/// The end of the streaming predict's block that starts at hole b of n: kPredictBlock holes,
/// but the last 2 × kPredictBlock in halves down to kLastBlock. With threads > 1, a block goes to
/// the sink while the next one is predicted; the last block's formatting is the one nothing
/// overlaps, so it is kept short.
size_t blockEnd(size_t b, size_t n) {
  const size_t left = n - b;
  if (left > 2 * kPredictBlock) return b + kPredictBlock;
  return b + std::min(left, std::max(kLastBlock, (left + 1) / 2));
}

/// Predicts requests [begin, end) into `out`, each seeded with the previous admissible solution;
/// `prev` carries it from block to block (PredictOptions::seed), so block by block gives the same
/// bytes as one call. The per-hole work runs on `threads` workers (resolvedThreads); the result
/// does not depend on the count (predictHoles fixes the IK seeds in a sequential pass first).
void predictRange(const PredictionModel& m, std::span<const HoleRequest> req, size_t begin,
                  size_t end, std::optional<Vec6>& prev, int threads,
                  std::vector<HolePrediction>& out) {
  PredictOptions o;
  o.threads = threads;
  o.seed = prev;
  out = predictHoles(m, req.subspan(begin, end - begin), o);
  for (const HolePrediction& h : out) {
    if (h.status == HoleStatus::kOk) prev = h.joints;
  }
}

}  // namespace

PredictionResult predictJob(const std::string& cell_path, const std::string& program_path,
                            const JobOptions& options, const ProgressFn& progress) {
  PredictionResult r;
  r.context = loadContext(cell_path, program_path, options);
  if (aimsAtRegisteredPart(r.context, options)) r.context.job.requests = registeredHoles(r.context);
  const int threads = resolvedThreads(options.threads);
  const auto& req = r.context.job.requests;
  r.holes.reserve(req.size());
  std::optional<Vec6> prev;
  std::vector<HolePrediction> block;
  for (size_t b = 0; b < req.size(); b += kPredictBlock) {
    const size_t e = std::min(req.size(), b + kPredictBlock);
    predictRange(r.context.model, req, b, e, prev, threads, block);
    for (HolePrediction& h : block) r.holes.push_back(std::move(h));
    if (progress) progress(e, req.size());
  }
  r.summary = summarize(r.holes);
  return r;
}

PredictionResult predictJobStreaming(
    const std::string& cell_path, const std::string& program_path, const JobOptions& options,
    const HoleSink& sink, const std::function<void(const PredictionContext&)>& on_context,
    const ProgressFn& progress) {
  const BlockSink each = [&sink](size_t first, std::span<const HolePrediction> holes,
                                 std::span<const HoleRequest> requests, int) {
    for (size_t k = 0; k < holes.size(); ++k) sink(first + k, holes[k], requests[k]);
  };
  return predictJobStreaming(cell_path, program_path, options, sink ? each : BlockSink(),
                             on_context, progress);
}

PredictionResult predictJobStreaming(
    const std::string& cell_path, const std::string& program_path, const JobOptions& options,
    const BlockSink& sink, const std::function<void(const PredictionContext&)>& on_context,
    const ProgressFn& progress) {
  PredictionResult r;
  const int threads = resolvedThreads(options.threads);
  // a program's holes are set up block by block as they are predicted (the memory of a block)
  r.context = loadContext(cell_path, program_path, options, true, true);
  const bool registered = aimsAtRegisteredPart(r.context, options);
  if (registered && !r.context.job.deferred) r.context.job.requests = registeredHoles(r.context);
  if (on_context) on_context(r.context);
  const JobHoles& job = r.context.job;
  const size_t n = job.deferred ? job.hole_count : job.requests.size();
  for (const HoleSource& s : job.sources) r.frames.add(s);
  SummaryAccumulator sum;
  struct Block {
    std::vector<HoleRequest> requests;  // deferred job: the block's own
    std::vector<HoleSource> sources;
    std::vector<HolePrediction> holes;
  };
  auto requestsOf = [&](const Block& blk, size_t b) {
    return job.deferred ? std::span<const HoleRequest>(blk.requests)
                        : std::span<const HoleRequest>(job.requests).subspan(b, blk.holes.size());
  };
  // With more than one thread, block k goes to the sink (JSON formatting and writing) on a task
  // of its own while block k + 1 is predicted: the sink still sees every hole once, in order, on
  // one thread at a time, so the bytes are those of one thread.
  auto drain = [&](const Block& blk, size_t b) {
    for (const HolePrediction& h : blk.holes) sum.add(h);
    if (sink) sink(b, blk.holes, requestsOf(blk, b), threads);
  };
  std::optional<Vec6> prev;
  std::array<Block, 2> blocks;
  std::future<void> draining;
  int k = 0;
  for (size_t b = 0, e = 0; b < n; b = e, k ^= 1) {
    e = blockEnd(b, n);
    Block& blk = blocks[static_cast<size_t>(k)];
    if (job.deferred) {
      setUpHoles(job, r.context.cell, r.context.robot, b, e, threads, blk.requests, blk.sources);
      if (registered) moveWithPart(partMotion(r.context.cell), blk.requests);
      for (const HoleSource& s : blk.sources) r.frames.add(s);
      predictRange(r.context.model, blk.requests, 0, e - b, prev, threads, blk.holes);
    } else {
      predictRange(r.context.model, job.requests, b, e, prev, threads, blk.holes);
    }
    if (draining.valid()) draining.get();  // the previous block is written (or its error thrown)
    if (threads > 1) {
      draining = std::async(std::launch::async, drain, std::cref(blk), b);
    } else {
      drain(blk, b);
    }
    if (progress) progress(e, n);
  }
  if (draining.valid()) draining.get();
  r.summary = sum.summary();
  return r;
}

CompensationResult compensateJob(const std::string& cell_path, const std::string& program_path,
                                 const CompensationJob& job, const ProgressFn& progress) {
  CompensationResult r = compensateJobHoles(cell_path, program_path, job, progress);
  editCompensatedProgram(r, job);
  return r;
}

CompensationResult loadCompensationJob(const std::string& cell_path,
                                       const std::string& program_path,
                                       const CompensationJob& job) {
  CompensationResult r;
  r.context = loadContext(cell_path, program_path, job.job);
  if (!r.context.job.program) throw InputError(program_path, 0, "not a program roprec can rewrite");
  if (const auto note = checkNotCompensated(*r.context.job.program, job.force))
    r.context.job.notes.push_back(*note);
  r.orientation = orientationModeName(job.options.mode);
  return r;
}

CompensationResult compensateJobHoles(const std::string& cell_path, const std::string& program_path,
                                      const CompensationJob& job, const ProgressFn& progress) {
  CompensationResult r = loadCompensationJob(cell_path, program_path, job);
  compensateLoadedHoles(r, job, progress);
  return r;
}

void compensateLoadedHoles(CompensationResult& r, const CompensationJob& job,
                           const ProgressFn& progress) {
  CompensationOptions options = job.options;
  options.threads = resolvedThreads(job.job.threads);  // the same bytes for any count
  if (r.context.cell.part_registration) {
    const std::vector<HoleRequest> aimed = registeredHoles(r.context);
    r.holes = compensateHoles(r.context.model, aimed, options, &r.stats);
  } else {
    r.holes = compensateHoles(r.context.model, r.context.job.requests, options, &r.stats);
  }
  if (progress) progress(r.holes.size(), r.holes.size());
  r.failed = static_cast<int>(
      std::count_if(r.holes.begin(), r.holes.end(), [](const auto& h) { return !h.ok; }));
  r.hole_count = r.holes.size();
}

void compensateLoadedStreaming(CompensationResult& r, const CompensationJob& job,
                               const CompensatedBlockSink& sink) {
  postproc::Program& prog = *r.context.job.program;
  // the recognised cycles are not read after the holes' set-up (requests and sources)
  std::vector<postproc::Hole>().swap(r.context.job.recognized);
  prog.position_min_decimals = 5;  // 0.01 µm: the written target carries the compensation
  // the marker first: the program's first file is written out as the holes are edited
  postproc::markCompensated(prog, markerText(r.context.cell, r.orientation));
  const int threads = resolvedThreads(job.job.threads);
  CompensationOptions options = job.options;
  options.threads = threads;  // the same bytes for any count
  const std::vector<HoleRequest>& req = r.context.job.requests;
  const std::vector<HoleSource>& sources = r.context.job.sources;
  const size_t n = req.size();
  // holes that share a target with another hole are edited in hole order (each reads what the
  // one before wrote), the others prepared on the workers
  const std::vector<char> shared =
      holesSharingTargets(sources, std::vector<char>(n, 1), prog.targets().size());
  // stable[i]: the first byte of the first file that the edits of holes i.. may change (the start
  // of the line of their earliest target there)
  const postproc::SourceFile& f0 = prog.files[0];
  std::vector<std::size_t> stable(n + 1, f0.bytes.size());
  for (size_t i = n; i-- > 0;) {
    std::size_t at = stable[i + 1];
    for (const int t : sources[i].targets) {
      const postproc::Target& tg = prog.targets()[static_cast<size_t>(t)];
      if (tg.file != 0 || tg.line < 1) continue;
      const auto l = static_cast<size_t>(tg.line - 1 - f0.line_base);
      at = std::min<std::size_t>(at, l < f0.line_starts.size() ? f0.line_starts[l] : 0);
    }
    stable[i] = at;
  }
  std::vector<postproc::EditLog> logs(std::min(n, kCompensationBlock));
  std::vector<std::vector<std::string>> refusals(logs.size());
  StatsCarry carry;
  const CompensationSink each = [&](size_t first, std::span<HoleCompensation> holes) {
    if (logs.size() < holes.size()) {  // stiffest may hand over a little more than a block
      logs.resize(holes.size());
      refusals.resize(holes.size());
    }
    parallelFor(holes.size(), threads, [&](int, size_t k) {
      logs[k].ops.clear();
      refusals[k].clear();
      if (holes[k].ok && !shared[first + k])
        editHoleTargets(r, holes[k], first + k, logs[k], refusals[k]);
    });
    for (size_t k = 0; k < holes.size(); ++k) {
      const size_t i = first + k;
      addHoleStats(r.summary, carry, req, i, holes[k], job.options.jump_threshold);
      if (!holes[k].ok) {
        ++r.failed;
        continue;
      }
      if (shared[i]) editHoleTargets(r, holes[k], i, logs[k], refusals[k]);
      postproc::applyEdits(prog, std::move(logs[k]));
      for (std::string& x : refusals[k]) r.refused.push_back(std::move(x));
    }
    sink(r, first, holes, stable[first + holes.size()]);
  };
  compensateJobHolesInBlocks(r, req, options, each);
  r.hole_count = n;
  settleWritable(r, job, n);
}

namespace {

/// The compensation edits of a KRL program read again by windows (postproc::ProgramStream), in
/// hole order: each hole's targets are edited in the window that holds them (a target of an
/// earlier window in that window's bytes), and the first file is written out up to the first
/// byte a later hole can still change (the line of the earliest target the reader keeps). The
/// edits and the bytes are those of editProgram on the program read whole.
class StreamedProgramEdits {
 public:
  StreamedProgramEdits(CompensationResult& r, int threads, ByteWriter write)
      : r_(r),
        threads_(threads),
        stream_(r.context.job.path, postproc::ProgramStream::kWindowBytes, threads > 1),
        edits_(stream_, std::move(write), markerText(r.context.cell, r.orientation),
               r.context.job.program->files[0]) {
    stream_.skipValueRanges();  // the first reading checked them
    postproc::Program& p = stream_.program();
    p.position_min_decimals = 5;  // 0.01 µm: the written target carries the compensation
    p.fanuc_turn_axes = r.context.job.program->fanuc_turn_axes;
    pinned_ = p.target_list.size();  // the .dat's: they stay, the reader numbers them first
  }

  /// Edits holes [first, first + holes.size()) (their results `holes`), refusals appended to
  /// r.refused in hole order.
  void edit(size_t first, std::span<const HoleCompensation> holes) {
    if (first != edited_) throw InternalError("StreamedProgramEdits: holes out of order");
    size_t k = 0;
    while (k < holes.size()) {
      if (pending_ == holes_.size()) {
        advance();
        continue;
      }
      const size_t m = std::min(holes_.size() - pending_, holes.size() - k);
      editBatch(holes.subspan(k, m));
      pending_ += m;
      k += m;
      edited_ += m;
    }
  }

  /// Reads the program to its end and writes the rest of the first file.
  void finish() {
    while (!ended_) {
      if (stream_.next()) {
        edits_.installed();
      } else {
        ended_ = true;
      }
    }
    edits_.finish();
  }

  /// The `.dat` with its edits, nullopt for a program without one.
  std::optional<std::string> dat() { return edits_.dat(); }

 private:
  /// An edit at a byte of the first file (or of the .dat), as EditLog::Op.
  struct FileEdit {
    bool erase{false};
    int file{0};
    std::uint64_t at{0};
    std::uint32_t length{0};
    std::string text;
  };
  /// Retires what no later hole reads, writes what no later edit changes, and reads on to the
  /// next holes.
  void advance() {
    if (!holes_.empty()) {
      const postproc::Hole& last = holes_.back();
      const size_t keep = std::min(static_cast<size_t>(last.bottom_motion), rec_.nextMotion() - 1);
      const postproc::Retired t = stream_.retire(keep);
      rec_.retired(t.motions, t.target_begin, t.target_end);
      retired_targets_ += t.target_end - t.target_begin;
    }
    holes_.clear();
    pending_ = 0;
    while (true) {
      edits_.flush();
      if (ended_) throw InternalError("StreamedProgramEdits: fewer holes than the first reading");
      if (stream_.next()) {
        edits_.installed();
        rec_.advance(stream_.program(), false);
      } else {
        ended_ = true;
        // the stream releases the last window's bytes at the end: its last holes read them
        if (const auto* w = edits_.latestWindow()) stream_.program().files[0].bytes = w->bytes;
        rec_.advance(stream_.program(), true);
      }
      holes_ = rec_.take();
      if (!holes_.empty()) return;
    }
  }

  /// Whether a target of `h` lies in a window before the stream's current one.
  bool inEarlierWindow(const postproc::Hole& h) {
    const postproc::Program& p = stream_.program();
    const int first_line = p.files[0].line_base + 1;
    return std::any_of(h.targets.begin(), h.targets.end(), [&](int t) {
      const postproc::Target& tg = p.targets()[static_cast<size_t>(t)];
      return tg.file == 0 && tg.line < first_line;
    });
  }

  /// The edits of hole `h` (result `c`) into `log`, its refusals into `refused`: editHoleTargets
  /// on the window's program. `swap`: a target of an earlier window is edited in its window's
  /// bytes (one thread at a time).
  void editHole(const postproc::Hole& h, const HoleCompensation& c, bool swap,
                std::vector<FileEdit>& log, std::vector<std::string>& refused) {
    postproc::Program& prog = stream_.program();
    const Pose T_W_frame = frameOf(h);
    postproc::EditLog one;
    for (const int t : h.targets) {
      const postproc::Target& tg = prog.targets()[static_cast<size_t>(t)];
      const CompensatedTarget ct = compensatedTarget(r_.context.cell, c, T_W_frame, prog, tg);
      postproc::StreamedEdits::Window* w = tg.file == 0 ? &edits_.windowOf(tg.line) : nullptr;
      const bool other = swap && w != nullptr && w != edits_.latestWindow();
      if (other) std::swap(prog.files[0].bytes, w->bytes);
      one.ops.clear();
      const postproc::EditResult er =
          postproc::replaceTargetPose(prog, t, T_W_frame.inverse() * ct.T_W, ct.config, one);
      if (other) std::swap(prog.files[0].bytes, w->bytes);
      for (postproc::EditLog::Op& op : one.ops) {
        const std::uint64_t base = op.edit.file == 0 ? w->start : 0;
        log.push_back(FileEdit{op.erase, op.edit.file, base + op.edit.offset, op.edit.length,
                               std::move(op.edit.text)});
      }
      if (!er.ok) {
        // the target's index in the program read whole: the targets retired before it counted
        const size_t global = static_cast<size_t>(t) >= pinned_
                                  ? static_cast<size_t>(t) + retired_targets_
                                  : static_cast<size_t>(t);
        refused.push_back("hole " + c.id + " target " +
                          (tg.name.empty() ? std::to_string(global) : tg.name) + ": " + er.reason);
      }
    }
  }

  /// The base frame of hole `h`'s targets (setUpHole's T_W_frame with the job's base frames:
  /// applyBaseFrame).
  Pose frameOf(const postproc::Hole& h) {
    const postproc::Program& p = stream_.program();
    const postproc::Frame* base = h.base >= 0 ? &p.frames[static_cast<size_t>(h.base)] : nullptr;
    if (base && base->resolved) return base->pose;
    const auto& given = r_.context.job.base_frames;
    if (h.base >= 0 && static_cast<size_t>(h.base) < given.size() &&
        given[static_cast<size_t>(h.base)])
      return *given[static_cast<size_t>(h.base)];
    return r_.context.cell.T_base_wobj;
  }

  /// Holes holes_[pending_ ..) with results `res`: the holes whose targets are their own and in
  /// this window edited on the workers, the others in hole order; the edits queued in hole order.
  void editBatch(std::span<const HoleCompensation> res) {
    const size_t m = res.size();
    serial_.assign(m, 0);
    // (target, hole) of the batch, sorted: a target two holes list is shared
    uses_.clear();
    for (size_t k = 0; k < m; ++k) {
      const postproc::Hole& h = holes_[pending_ + k];
      for (const int t : h.targets) uses_.emplace_back(t, k);
      if (inEarlierWindow(h)) serial_[k] = 1;
    }
    std::sort(uses_.begin(), uses_.end());
    uses_.erase(std::unique(uses_.begin(), uses_.end()), uses_.end());
    for (size_t u = 0; u + 1 < uses_.size(); ++u) {
      if (uses_[u].first != uses_[u + 1].first) continue;
      serial_[uses_[u].second] = 1;
      serial_[uses_[u + 1].second] = 1;
    }
    if (logs_.size() < m) {
      logs_.resize(m);
      refusals_.resize(m);
    }
    parallelFor(m, threads_, [&](int, size_t k) {
      logs_[k].clear();
      refusals_[k].clear();
      if (res[k].ok && !serial_[k])
        editHole(holes_[pending_ + k], res[k], false, logs_[k], refusals_[k]);
    });
    for (size_t k = 0; k < m; ++k) {
      if (!res[k].ok) continue;
      if (serial_[k]) editHole(holes_[pending_ + k], res[k], true, logs_[k], refusals_[k]);
      for (FileEdit& e : logs_[k]) edits_.put(e.erase, e.file, e.at, e.length, std::move(e.text));
      logs_[k].clear();
      for (std::string& x : refusals_[k]) r_.refused.push_back(std::move(x));
    }
  }

  CompensationResult& r_;
  int threads_;
  postproc::ProgramStream stream_;
  postproc::StreamedEdits edits_;  ///< the windows' bytes, the queued edits, the writing
  postproc::HoleRecognizer rec_;
  std::vector<postproc::Hole> holes_;  ///< the holes recognised in the window
  size_t pending_{0};                  ///< holes_[pending_ ..] not edited yet
  size_t edited_{0};                   ///< holes edited so far
  bool ended_{false};
  size_t retired_targets_{0};
  size_t pinned_{0};
  std::vector<char> serial_;
  std::vector<std::pair<int, size_t>> uses_;
  std::vector<std::vector<FileEdit>> logs_;
  std::vector<std::vector<std::string>> refusals_;
};

constexpr std::string_view kMarker = "roprec compensated";

/// Whether bytes [begin, end) of `path` hold the compensation marker (read in pieces); true
/// when the file cannot be read (the whole-program path states why).
bool rangeHoldsMarker(const std::string& path, std::uint64_t begin, std::uint64_t end) {
  std::ifstream in(path, std::ios::binary);  // a 64-bit offset on every platform
  if (!in || !in.seekg(static_cast<std::streamoff>(begin))) return true;
  std::string buf(std::size_t{4} << 20U, '\0');
  std::size_t kept = 0;
  std::uint64_t at = begin;
  bool found = false;
  while (!found && at < end) {
    const std::size_t want =
        static_cast<std::size_t>(std::min<std::uint64_t>(buf.size() - kept, end - at));
    in.read(buf.data() + kept, static_cast<std::streamsize>(want));
    const auto n = static_cast<std::size_t>(in.gcount());
    if (n == 0) break;
    at += n;
    const std::string_view v(buf.data(), kept + n);
    found = v.find(kMarker) != std::string_view::npos;
    kept = std::min(v.size(), kMarker.size() - 1);
    std::memmove(buf.data(), buf.data() + v.size() - kept, kept);
  }
  return found;
}

}  // namespace

bool fileHoldsMarker(const std::string& path) {
  constexpr std::uint64_t kSplit = std::uint64_t{16} << 20U;  // below: one thread
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec || size < kSplit)
    return rangeHoldsMarker(path, 0, std::numeric_limits<std::uint64_t>::max());
  const std::uint64_t mid = size / 2;
  auto second = std::async(std::launch::async, [&path, mid] {
    return rangeHoldsMarker(path, mid - kMarker.size(), std::numeric_limits<std::uint64_t>::max());
  });
  const bool first = rangeHoldsMarker(path, 0, mid);
  return second.get() || first;
}

bool compensationStreams(const std::string& program_path, const CompensationJob& job,
                         bool marked_too) {
  if (job.job.holes) return false;
  try {
    postproc::ProgramStream s(program_path);
    if (!s.windowed()) return false;
    const std::vector<postproc::SourceFile>& files = s.program().files;
    // the .dat is held whole either way (its targets stay): a program whose .dat is the larger
    // file, above a window, gains nothing from a .src read by windows, read twice
    std::error_code ec;
    const auto src_bytes = std::filesystem::file_size(files[0].path, ec);
    if (files.size() > 1 && !ec && files[1].bytes.size() > postproc::ProgramStream::kWindowBytes &&
        files[1].bytes.size() >= src_bytes)
      return false;
    if (marked_too) return true;
    for (const postproc::SourceFile& f : files) {
      if (fileHoldsMarker(f.path)) return false;
    }
  } catch (const InputError&) {
    return false;  // the whole-program path gives the error
  }
  return true;
}

CompensationResult loadStreamedCompensationJob(const std::string& cell_path,
                                               const std::string& program_path,
                                               const CompensationJob& job) {
  CompensationResult r;
  r.context = loadContext(cell_path, program_path, job.job, true, true, true);
  if (!r.context.job.program || !r.context.job.streamed)
    throw InternalError("loadStreamedCompensationJob: the program is not read by windows");
  // the frames the options give the base frames the program does not define (resolved above)
  applyBaseFrames(r.context.job, r.context.cell);
  std::vector<int>().swap(r.context.job.undefined_base);
  r.orientation = orientationModeName(job.options.mode);
  return r;
}

void compensateStreamedProgram(CompensationResult& r, const CompensationJob& job,
                               const ByteWriter& write_src, std::optional<std::string>& dat,
                               const StreamedBlockSink& sink) {
  const int threads = resolvedThreads(job.job.threads);
  // every hole's request, kept from the first reading (the sequence is chosen over the whole
  // program)
  const std::vector<HoleRequest>& req = r.context.job.requests;
  const size_t n = req.size();
  if (n != r.context.job.hole_count)
    throw InternalError("compensateStreamedProgram: the job's requests were not kept");
  CompensationOptions options = job.options;
  options.threads = threads;  // the same bytes for any count
  // the second reading edits the program as the holes are compensated
  StreamedProgramEdits edits(r, threads, write_src);
  StatsCarry carry;
  const CompensationSink each = [&](size_t first, std::span<HoleCompensation> done) {
    for (size_t k = 0; k < done.size(); ++k) {
      addHoleStats(r.summary, carry, req, first + k, done[k], job.options.jump_threshold);
      if (!done[k].ok) ++r.failed;
    }
    edits.edit(first, done);
    sink(first, done, std::span<const HoleRequest>(req).subspan(first, done.size()));
  };
  compensateJobHolesInBlocks(r, req, options, each);
  r.hole_count = n;
  settleWritable(r, job, n);
  if (!r.writable) return;
  edits.finish();
  dat = edits.dat();
}

void editCompensatedProgram(CompensationResult& r, const CompensationJob& job) {
  r.refused = editProgram(r, resolvedThreads(job.job.threads));
  postproc::markCompensated(*r.context.job.program, markerText(r.context.cell, r.orientation));
  r.summary = compensationStats(r, job.options.jump_threshold);
  settleWritable(r, job, r.holes.size());
}

std::optional<std::string> checkNotCompensated(const postproc::Program& program, bool force) {
  const std::optional<postproc::MarkerLocation> m = postproc::findCompensationMarker(program);
  if (!m) return std::nullopt;
  const std::string& file = program.files[static_cast<size_t>(m->file)].path;
  if (!force) {
    throw InputError(file, m->line,
                     "the program was already compensated by roprec (\"" + m->text +
                         "\"); compensating it again would apply the correction twice. "
                         "Compensate the original program, or give --force to do it anyway");
  }
  return "--force: the program was already compensated by roprec (" + file + ":" +
         std::to_string(m->line) + "); the correction is applied again on top of it";
}

void refuseOverwritingInput(const postproc::Program& program,
                            const std::vector<std::string>& outs) {
  std::vector<std::string> inputs;
  for (const auto& f : program.files) inputs.push_back(f.path);
  if (!program.dat_path.empty()) inputs.push_back(program.dat_path);
  for (const std::string& o : outs) {
    for (const std::string& in : inputs) {
      if (sameFile(o, in)) {
        std::string msg = "output " + o;
        msg += " is the input file " + in;
        msg += ": write the compensated program to another file (nothing written)";
        throw UsageError(msg);
      }
    }
  }
}

std::vector<std::string> writeCompensatedProgram(
    PredictionContext& context, const std::string& program_out,
    const std::vector<std::pair<std::string, std::string>>& extra) {
  if (!context.job.program)
    throw InputError(context.job.path, 0, "not a program roprec can rewrite");
  std::vector<std::string> outs = postproc::outputPaths(*context.job.program, program_out);
  for (const auto& e : extra) outs.push_back(e.first);
  refuseOverwritingInput(*context.job.program, outs);
  postproc::writeProgram(*context.job.program, program_out);
  std::vector<std::string> written = postproc::outputPaths(*context.job.program, program_out);
  for (const auto& [path, text] : extra) {
    writeFileAtomic(path, text);
    written.push_back(path);
  }
  return written;
}

}  // namespace roprec::api
