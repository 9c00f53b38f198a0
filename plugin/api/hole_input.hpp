#pragma once
/// \file hole_input.hpp
/// The holes of a job, from a robot program (any dialect postproc reads: drill cycles recognised
/// per docs/programs.md §8.2) or from the contract's hole-list CSV, as prediction requests in the
/// robot base frame.
///
/// Frames: a program target is T_frame_tcp in the program's base frame (KUKA $BASE/BASE_DATA,
/// ABB wobj, FANUC UFRAME). When the program defines that frame it is used; when it does not
/// (e.g. BASE_DATA[n] lives in the controller's $config.dat) the cell's <workobject> is taken as
/// the program's base frame and a note says so. Hole-list rows are in the cell's workobject frame;
/// their TCP orientation: z = drilling direction, x = the workobject x axis projected ⊥ z (the
/// workobject y axis when the direction is within 26° of x) — the rotation about the drill axis is
/// free and `roprec compensate --orientation` may change it.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compensator/precision/cell.hpp"
#include "compensator/precision/prediction.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"

namespace roprec::api {

/// Job notes about a value or frame the program refers to but roprec could not resolve start
/// with this prefix; the CLI prints them as warnings.
inline constexpr const char* kUnresolvedPrefix = "unresolved ";

struct HoleSource {
  int hole{-1};              ///< index into `recognized` (programs)
  int base{-1};              ///< the program frame of the hole's base (index into frames)
  std::vector<int> targets;  ///< program targets of the cycle (all move together when compensated)
  int bottom_target{-1};
  Pose T_W_frame{Pose::Identity()};  ///< base frame of the program frame the target is in
  bool frame_resolved{false};
  std::string frame_ref;
  std::optional<Pose> T_W_tcp_spec;  ///< hole-list nominal pose when a hole list was matched
};

/// The frame every hole's targets are given in, if they share one (the report's part frame),
/// gathered hole by hole: the first hole's frame while every later one has the same name and a
/// pose within 1e-12 of it.
class SharedFrame {
 public:
  void add(const HoleSource& s) {
    if (!first_) {
      first_ = s;
      first_->targets.clear();
      return;
    }
    shared_ = shared_ && s.frame_ref == first_->frame_ref &&
              s.T_W_frame.isApprox(first_->T_W_frame, 1e-12);
  }
  /// The shared frame's source (frame_ref, T_W_frame), nullptr when there is none (no hole, or
  /// two frames).
  [[nodiscard]] const HoleSource* shared() const { return first_ && shared_ ? &*first_ : nullptr; }

 private:
  std::optional<HoleSource> first_;
  bool shared_{true};
};

/// What the job's frame and tool resolution needs of a hole (resolveFramesAndTool in job.cpp):
/// the hole, its base frame and the tool, file and line of its drill point's motion. A job keeps
/// those of the first hole of each base frame and of each tool (the others repeat them).
struct HoleFrameUse {
  std::string id;
  int base{-1};  ///< index into the program's frames (-1: none named)
  int tool{-1};  ///< the bottom motion's tool, index into the program's frames
  int file{-1};  ///< the bottom motion's file (index into the program's files) and line
  int line{0};
};

class ProgramHoles;

struct JobHoles {
  std::string path;
  bool is_hole_list{false};
  std::optional<postproc::Program> program;
  std::vector<postproc::Hole> recognized;
  std::vector<HoleRequest> requests;
  std::vector<HoleSource> sources;
  std::vector<std::string> notes;
  /// Set up on demand (loadJobHoles with `defer_setup`): `requests` and `sources` stay empty and
  /// setUpHoles() builds those of a range of holes (predictJobStreaming holds one block's).
  bool deferred{false};
  /// A deferred KRL program read by windows (postproc::ProgramStream): `recognized` stays empty,
  /// `program` holds its frames, notes and unresolved references (not its motions), and
  /// setUpHoles() reads the program again, in hole order, as the holes are asked for.
  bool streamed{false};
  std::size_t hole_count{0};  ///< the job's holes (every kind of job)
  std::string first_hole_id;
  std::vector<HoleFrameUse> frame_uses;
  std::shared_ptr<ProgramHoles> stream;  ///< streamed: the second reading (setUpHoles)
  /// Streamed with its requests kept (loadJobHoles' keep_requests): per hole the program frame
  /// of its base when the program does not define it (-1: defined, or none named), the frame
  /// JobHoles::base_frames may give it (applyBaseFrames).
  std::vector<int> undefined_base;
  /// Per program frame (index into program->frames): the pose the job gives a base frame the
  /// program does not define (--frame, --frame cell: see resolveFramesAndTool in job.cpp), for
  /// the holes drilled in that frame (applyBaseFrame).
  std::vector<std::optional<Pose>> base_frames;
};

/// Moves a hole's request and source into the pose JobHoles::base_frames gives its program base
/// frame, when it has one and the program does not define that frame:
/// T_W_tcp ← T · T_W_frame⁻¹ · T_W_tcp, T_W_frame ← T.
void applyBaseFrame(const JobHoles& job, HoleRequest& r, HoleSource& src);

/// Moves the requests a streamed job kept (loadJobHoles' keep_requests) into the poses
/// JobHoles::base_frames gives their base frames (applyBaseFrame, hole by hole).
void applyBaseFrames(JobHoles& job, const CellSpec& cell);

/// The requests and sources of holes [begin, end) of a deferred job (JobHoles::deferred), set up
/// on `threads` workers with the job's base frames applied: the values loadJobHoles gives when
/// it does not defer. Throws InputError as loadJobHoles does (the first failing hole in order).
/// A streamed job's holes are asked for in order (`begin` = the previous call's `end`); with
/// threads > 1 a task of its own reads and sets them up, up to two windows ahead.
void setUpHoles(const JobHoles& job, const CellSpec& cell, const Robot& robot, size_t begin,
                size_t end, int threads, std::vector<HoleRequest>& requests,
                std::vector<HoleSource>& sources);

/// Per hole, whether it shares a program target with another hole: over the holes with
/// `included[i]` != 0, of a program with `targets` targets. A target a hole lists twice (in and
/// out through one approach point) is not shared. Holes that share targets must be edited in
/// hole order, the others may be edited at the same time.
std::vector<char> holesSharingTargets(const std::vector<HoleSource>& sources,
                                      const std::vector<char>& included, std::size_t targets);

/// The key a program names a tool by, as the cell's tool table keys its drills (<drill tool>):
/// `TOOL_DATA[3]` (KRL) and `UTOOL[3]` (FANUC) → "3", a RAPID tooldata name as it is.
std::string programToolKey(const std::string& ref);

/// Throws InputError at the first motion whose position was taught in another tool than the one
/// the program selected before it (postproc::ToolConflict, FANUC UTOOL_NUM against a position's
/// UT): the controller stops there, so the program cannot run as written (exit 2, with a hint).
void refuseToolConflicts(const postproc::Program& p);
/// The cell's <drill> elements in document order (ProcessSpec::drills); empty without a drilling
/// process.
std::vector<const XmlNode*> cellDrills(const CellSpec& cell);

/// Sets r.drill and r.tool: the drill of the cell's tool table (docs/process.md §8, tool table)
/// keyed by `tool` (a program's tool key, programToolKey, or a hole list's tool column; `named_as`
/// is how the job names it), else the one drill of r.diameter. Throws InputError at `file:line`
/// when the table has no such tool or nothing says which drill. A cell without a tool table (one
/// drill): nothing to do (r.drill stays -1, the cell's drill).
void assignDrill(const CellSpec& cell, const std::string& tool, const std::string& named_as,
                 const std::string& file, int line, HoleRequest& r);

/// TCP rotation for a drilling direction (see the file comment), in the frame of `direction`.
Mat3 holeFrame(const Vec3& direction);

/// Reads the job. `hole_list` (optional CSV) supplies ids, diameters and tolerances for the holes
/// of a program (matched by id, else by position within `match_tol_mm`; O((n + m) log) through
/// a hash of the ids and a grid of the positions). Throws InputError (the hole list's first row)
/// when the list matches none of the job's holes; a partial match adds two notes starting
/// "--holes:" listing the job holes without a list entry and the entries without a hole. Bad
/// hole lists throw InputError `FILE:LINE: what` (postproc::parseHoleList).
/// The holes' requests are set up on `threads` workers (the same requests, notes and errors).
/// `defer_setup` (a job that writes no program; a program without a hole list): every hole is
/// checked (the same errors) but the requests are not kept: setUpHoles() builds them block by
/// block (JobHoles::deferred); the program's files' bytes are released once it is read (its
/// targets, motions and frames stay; its files keep their paths and lines). A deferred KRL
/// program is read by windows instead (JobHoles::streamed): every hole checked on a first
/// reading that keeps no motion behind the window, the holes set up on a second.
/// `keep_requests` (a streamed program): the first reading keeps every hole's request as set up
/// there (`requests`, no base frame of JobHoles::base_frames applied yet: applyBaseFrames) and
/// gives no second reading (`stream` stays empty).
JobHoles loadJobHoles(const std::string& path, const CellSpec& cell, const Robot& robot,
                      const std::optional<std::string>& hole_list, double match_tol_mm = 0.5,
                      int threads = 1, bool defer_setup = false, bool keep_requests = false);

}  // namespace roprec::api
