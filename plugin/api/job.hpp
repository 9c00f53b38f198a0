#pragma once
/// \file job.hpp
/// The host-facing job API: a cell + a program (or a hole list) + options in, predictions,
/// compensations and the files a host writes out. Everything the `roprec predict` and
/// `roprec compensate` commands do, with no argument parsing and no printing; the CLI, the C ABI
/// (`plugin/c/roprec.h`) and the Python module are thin layers over it.
///
/// Units: SI inside every struct (m, rad, N); files and JSON in mm, deg, µm (docs/contract.md).
/// Errors: bad input throws roprec::InputError (`FILE:LINE: what`) or roprec::UsageError; a hole
/// that cannot be handled is a per-hole status, never an exception.
/// Thread safety: the functions here share no state; distinct jobs may run on distinct threads.

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "compensator/compensation/compensation.hpp"
#include "compensator/compensation/milling_compensation.hpp"
#include "compensator/precision/prediction.hpp"
#include "compensator/support/atomic_file.hpp"
#include "plugin/api/milling_job.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "plugin/api/program_frames.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// The library version ("0.2.0").
const char* version();

/// Called after each hole with (done, total); may be empty.
using ProgressFn = std::function<void(size_t, size_t)>;

/// How a job's holes are read.
struct JobOptions {
  std::optional<std::string> holes;  ///< hole-list CSV matched to the program's holes
  double match_tol_mm{0.5};          ///< position match when ids differ, mm
  std::string uncertainty;           ///< "" (the cell's), "linear" or "montecarlo"
  std::optional<std::array<int, 3>> fanuc_turn_axes;  ///< overrides the cell's <controller>
  /// How a program's base frame that only the controller defines (FANUC `UFRAME[n]`, KUKA
  /// `BASE_DATA[n]`, an ABB wobjdata declared without value) is resolved. Without any of these
  /// such a frame is an error (docs/programs.md §15):
  bool frame_cell{false};          ///< --frame cell: the cell's <workobject> is that frame
  std::optional<Pose> frame_pose;  ///< --frame "x y z a b c": every such base frame, robot base
  std::vector<FrameDefinition> frames;  ///< --frame 'REF=x y z a b c;...': by name (base or tool)
  /// How the program's tool is reconciled with the cell's when they differ (or when the program's
  /// tool is defined only on the controller: FANUC `UTOOL[n]`, KUKA `TOOL_DATA[n]`): "" = error,
  /// "program" = the program's TCP is the real one (the cell's mass data kept), "cell" = the
  /// cell's TCP is the real one (the program's targets are taken as TCP poses of it).
  std::string tool;
  /// Worker threads for the per-hole work (`--threads`): 1 (the default) runs on the calling
  /// thread, 0 takes every core (std::thread::hardware_concurrency). Outputs are byte-identical
  /// whatever the count (the sequential parts — IK seeds, the orientation sequence — are fixed
  /// before the per-hole work is shared out).
  int threads{1};
  /// predict: when the cell has a <part_registration> (verify --write-cell), every hole is aimed
  /// where the registration found the part — each pose and point of a request moved by
  /// partMotion, as compensate aims them — so its deviations and verdict are those of the real
  /// drilled point of the hole aimed at the registered part from that hole (compensate's
  /// "before"). verify sets false: it predicts the program as it was drilled and moves the
  /// nominal holes itself.
  bool registered_part{true};
};

/// `threads` with 0 resolved to the number of cores (at least 1). Throws UsageError when < 0.
int resolvedThreads(int threads);

/// Notes of a job that state how frames and the tool were resolved start with this prefix; the
/// CLI prints them on stderr and the reports show them in their header.
inline constexpr const char* kResolutionPrefix = "resolution: ";

// ---------------------------------------------------------------- predict

struct PredictionResult {
  PredictionContext context;          ///< cell, robot, job holes, model
  std::vector<HolePrediction> holes;  ///< one per context.job.requests entry
  CapabilitySummary summary;
  /// The frame every hole's targets share (predictJobStreaming: gathered block by block; the
  /// report's part frame).
  SharedFrame frames;
  /// Holes whose status is not kOk.
  [[nodiscard]] int failed() const;
};

/// Predicts every hole of `program` (each seeded with the previous admissible solution, or with
/// the request's own `ik_seed`). Throws InputError/UsageError on bad input.
PredictionResult predictJob(const std::string& cell_path, const std::string& program_path,
                            const JobOptions& options = {}, const ProgressFn& progress = {});

/// Receives each predicted hole once, in hole order (index into context.job.requests). With
/// options.threads > 1 the calls come from a task of their own (one call at a time, all done
/// before predictJobStreaming returns) while the next block of holes is predicted.
using HoleSink =
    std::function<void(size_t index, const HolePrediction& hole, const HoleRequest& request)>;

/// Receives the predicted holes a block at a time, in hole order: `holes[k]` is the hole of
/// `requests[k]` = context.job.requests[first + k]. The calls come as a HoleSink's do (one at a
/// time; with threads > 1 from a task of their own while the next block is predicted);
/// `threads` is the job's thread count, for a sink that formats a block on several workers.
using BlockSink = std::function<void(size_t first, std::span<const HolePrediction> holes,
                                     std::span<const HoleRequest> requests, int threads)>;

/// predictJob in constant memory: the holes are predicted in blocks and handed to `sink` in
/// order, then dropped; the result's `holes` stays empty and its `summary` is the one
/// summarize() gives over every hole. `on_context` (may be empty) is called once the job is
/// loaded, before the first hole (a writer's header). Same predictions, same order as predictJob.
/// A program's holes are set up block by block and its files' bytes released once it is read (a
/// predict writes no program): see loadJobHoles' `defer_setup`; the result's context.job.requests
/// and sources then stay empty (a hole list's are kept).
PredictionResult predictJobStreaming(
    const std::string& cell_path, const std::string& program_path, const JobOptions& options,
    const BlockSink& sink, const std::function<void(const PredictionContext&)>& on_context,
    const ProgressFn& progress = {});
/// The same with the holes handed over one by one.
PredictionResult predictJobStreaming(
    const std::string& cell_path, const std::string& program_path, const JobOptions& options,
    const HoleSink& sink, const std::function<void(const PredictionContext&)>& on_context,
    const ProgressFn& progress = {});

// ---------------------------------------------------------------- compensate

struct CompensationJob {
  JobOptions job;
  CompensationOptions options;  ///< orientation mode, grid, wrist margin, jumps
  bool allow_partial{false};    ///< keep the original targets of failed holes
  /// Compensate a program that carries roprec's "compensated" marker anyway (the correction is
  /// then applied a second time on top of the first).
  bool force{false};
};

/// Drilling-job compensation: per hole the compensated target; the edited program (every target
/// of a drill cycle moves with its drill point) in `context.job.program`.
struct CompensationResult {
  PredictionContext context;
  std::vector<HoleCompensation> holes;  ///< empty after compensateLoadedStreaming
  std::size_t hole_count{0};            ///< holes compensated or not (holes.size() when kept)
  CompensationStats stats;
  std::string orientation;           ///< "keep", "flip-free" or "stiffest"
  std::vector<std::string> refused;  ///< target edits the dialect writer refused
  int failed{0};                     ///< holes not compensated
  /// Statistics of the run (µm; counts) for a summary.
  struct Stats {
    std::vector<double> error_before_um;  ///< position error ⊥ axis of every predicted hole
    std::vector<double> residual_after_um;
    int conform_before{0};
    int conform_after{0};
    int jumps_before{0};  ///< axis-4/6 jumps > threshold between holes of a face
    int jumps_after{0};
  } summary;
  /// True when the program may be written: nothing failed (or allow_partial) and no edit refused
  /// (or allow_partial).
  bool writable{false};
  std::string why_not_writable;
};

/// Compensates every hole of a drilling program (a milling cell: see compensateMillingJob).
/// Throws InputError/UsageError on bad input (a hole list is not a program to rewrite).
/// compensateJobHoles then editCompensatedProgram.
CompensationResult compensateJob(const std::string& cell_path, const std::string& program_path,
                                 const CompensationJob& job = {}, const ProgressFn& progress = {});
/// compensateJob's first stage: the job loaded and its holes compensated (`holes`, `failed`,
/// `orientation`, `stats` final; the program not yet edited). What depends on the holes alone
/// (the targets export) can be written from here on, on another thread, while the second stage
/// edits the program: that stage writes only the program, `refused`, `summary`, `writable` and
/// `why_not_writable`.
CompensationResult compensateJobHoles(const std::string& cell_path, const std::string& program_path,
                                      const CompensationJob& job, const ProgressFn& progress = {});
/// compensateJobHoles' first part: the job loaded (context, the "compensated" marker checked,
/// `orientation`), no hole compensated yet.
CompensationResult loadCompensationJob(const std::string& cell_path,
                                       const std::string& program_path, const CompensationJob& job);
/// compensateJobHoles' second part, on a job loadCompensationJob loaded.
void compensateLoadedHoles(CompensationResult& r, const CompensationJob& job,
                           const ProgressFn& progress = {});

/// Receives the compensated holes of compensateLoadedStreaming a block at a time, in hole order:
/// holes[k] is hole first + k (request r.context.job.requests[first + k]); their targets' edits
/// are queued in the program, and every edit of the later holes lies at or after byte `stable` of
/// the program's first file (postproc::EditedFileWriter::flushBefore(stable) writes what is
/// final). The holes are dropped after the call.
using CompensatedBlockSink =
    std::function<void(CompensationResult& r, std::size_t first,
                       std::span<const HoleCompensation> holes, std::size_t stable)>;
/// compensateLoadedHoles and editCompensatedProgram in one pass that holds the results of one
/// block of holes at a time (kCompensationBlock): the compensation marker is queued first, then
/// each block's targets are edited and the block handed to `sink`. r.holes stays empty; at the
/// end `hole_count`, `failed`, `stats`, `refused`, `summary`, `writable` and `why_not_writable`
/// are those of compensateJob (the edits and the program's bytes too).
void compensateLoadedStreaming(CompensationResult& r, const CompensationJob& job,
                               const CompensatedBlockSink& sink);

/// Whether the file `path` holds the bytes of the compensation marker (postproc::kMarker): a
/// large file's halves read on two threads.
bool fileHoldsMarker(const std::string& path);
/// Whether compensate reads `program_path` by windows (loadStreamedCompensationJob): a KUKA KRL
/// program (postproc::ProgramStream), no hole list, and no "roprec compensated" marker in its
/// files (a marked program takes the whole-program path, which states where the marker is);
/// with `marked_too` a marked program as well (the marker is not searched).
bool compensationStreams(const std::string& program_path, const CompensationJob& job,
                         bool marked_too = false);
/// loadCompensationJob of a program compensationStreams() accepts, read by windows: every hole
/// checked and its request kept on a first reading (the same errors, notes and requests) that
/// keeps the program's frames, files and notes, not its motions or bytes; context.job is a
/// streamed job (JobHoles::streamed) with every request.
CompensationResult loadStreamedCompensationJob(const std::string& cell_path,
                                               const std::string& program_path,
                                               const CompensationJob& job);
/// Receives the compensated holes of compensateStreamedProgram a block at a time, in hole
/// order, with their requests (holes[k] is hole first + k); the holes are dropped after the call.
using StreamedBlockSink =
    std::function<void(std::size_t first, std::span<const HoleCompensation> holes,
                       std::span<const HoleRequest> requests)>;
/// compensateLoadedStreaming of a job loadStreamedCompensationJob loaded (its first reading kept
/// every hole's request: the sequence is chosen over the whole program): the holes are
/// compensated a block at a time while a second reading edits the program window by window; the
/// first file's bytes no later edit can change are written to `write_src` as they are final (the
/// rest once the program may be written), and `dat` receives the edited `.dat` (when the program
/// has one and may be written). The bytes, `failed`, `stats`, `refused`, `summary`, `writable` and
/// `why_not_writable` are those of compensateJob; memory does not hold the program.
void compensateStreamedProgram(CompensationResult& r, const CompensationJob& job,
                               const ByteWriter& write_src, std::optional<std::string>& dat,
                               const StreamedBlockSink& sink);

/// compensateJob's second stage: every compensated hole's targets edited in the program, the
/// compensation marker, the before/after summary and whether the program may be written.
void editCompensatedProgram(CompensationResult& r, const CompensationJob& job);

/// The marker line written into every compensated program (cell, version, mode).
std::string markerText(const CellSpec& cell, const std::string& mode);

/// Throws InputError (the marker's FILE:LINE) when the program carries roprec's "compensated"
/// marker and `force` is false; with `force` returns a note saying it was compensated again.
std::optional<std::string> checkNotCompensated(const postproc::Program& program, bool force);

/// Throws UsageError when an output path (the program's, its `.dat`, or an extra one) is one of
/// the program's input files (same path or same file by inode).
void refuseOverwritingInput(const postproc::Program& program, const std::vector<std::string>& outs);

/// Writes the outputs of a compensation all together: the program (and its .dat etc.) to
/// `program_out`, and each (path, text) of `extra`. Returns the paths written. Refuses (UsageError)
/// an output that is one of the input program's files; nothing is written then.
std::vector<std::string> writeCompensatedProgram(
    PredictionContext& context, const std::string& program_out,
    const std::vector<std::pair<std::string, std::string>>& extra);

}  // namespace roprec::api

#include "plugin/api/session.hpp"             // IWYU pragma: export
#include "plugin/report/exports.hpp"          // IWYU pragma: export
#include "plugin/report/prediction_json.hpp"  // IWYU pragma: export
