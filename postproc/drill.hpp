#pragma once
/// \file drill.hpp
/// Drill-point recognition (docs/programs.md §8.2) and matching to the contract's hole list.
///
/// A drill cycle is a maximal run of consecutive motions whose Cartesian targets lie on one line
/// through the first target, along its drilling axis a = R_first · tool_axis (|Δp × a| < line
/// tolerance), with constant orientation (< orientation tolerance), one tool and one base, all
/// after the first being linear moves, that goes into the material (some target deeper than the
/// first along +a) and carries process evidence: a feed slower than the run's fastest move, a
/// spindle/drill call or a drilling comment (a dwell alone is none: pick-and-place dwells too). The
/// drill point ("bottom") is the deepest target along +a; the surface is the point the first feed
/// move into the material starts from (approach and clearance moves run at the faster approach
/// speed); depth = bottom − surface. Every target of the run moves together when compensated. A
/// TP/KRL call of a drilling macro after a single target also makes a hole (entry = bottom = that
/// target).
///
/// Convention: roprec's drilling axis is the TCP +z axis (into the material) for every vendor;
/// `RecognitionOptions::tool_axis` changes it (e.g. +x for a KUKA tool with X tool direction).

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/program.hpp"

namespace roprec::postproc {

struct RecognitionOptions {
  Vec3 tool_axis{0, 0, 1};   ///< drilling axis in the TCP frame (unit)
  double line_tol_mm{0.05};  ///< |Δp × a| tolerance
  double ori_tol_deg{0.05};  ///< orientation constancy
  /// Also take a cycle whose only evidence is a dwell, marked Hole::dwell_only: a candidate that
  /// only a hole list can confirm (confirmedByHoleList).
  bool dwell_candidates{false};
};

struct Hole {
  std::string id;         ///< `H1`, `H2`… in program order (or the matched hole-list id)
  int entry_target{-1};   ///< first target of the cycle
  int bottom_target{-1};  ///< deepest target (the drill point)
  int entry_motion{-1};
  int bottom_motion{-1};
  std::vector<int> targets;     ///< every target of the cycle (distinct, program order)
  Vec3 position{Vec3::Zero()};  ///< bottom point in the base frame's coordinates of the program (m)
  Vec3 axis{Vec3::UnitZ()};     ///< drilling direction, same frame (unit)
  /// Where the hole starts: the point the feed starts from (the first move into the material at
  /// a speed slower than the cycle's approach/retract speed), on the axis, same frame (m). The
  /// approach point above it is not the surface (docs/programs.md §8.2).
  Vec3 surface{Vec3::Zero()};
  int surface_motion{-1};  ///< motion whose target is the surface point (-1: not recognised)
  /// Bottom depth below the surface along axis (m); 0 when the cycle shows no feed change (then
  /// the surface is not known from the program and the cell's declared depth applies).
  double depth{0.0};
  int base{-1};  ///< index into Program::frames
  int tool{-1};
  /// The evidence of drilling, kept as where to find it (no text per hole; holeEvidence renders
  /// it): a feed slower than approach/retract, the drilling markers of motions
  /// [marker_begin, marker_end) (all markers of that range when `all_markers`: a macro call), an
  /// exact stop at the bottom, no feed change.
  bool slower_feed{false};
  bool fine_bottom{false};
  bool no_feed_change{false};
  bool all_markers{false};
  bool dwell_only{false};  ///< a dwell is its only evidence (RecognitionOptions::dwell_candidates)
  int marker_begin{0};
  int marker_end{0};
};

std::vector<Hole> recognizeHoles(const Program& p, const RecognitionOptions& o = {});

/// recognizeHoles over a program that grows (read or made a block at a time): advance(p,
/// false) recognises the cycles of the motions read so far that are complete (the motion after
/// the cycle is read, so the cycle and its markers can no longer change) and keeps its place;
/// advance(p, true) at the end of the program recognises the rest. The same Program, grown by
/// reading, must be passed each time; the holes are then those recognizeHoles gives for the
/// whole program (recognizeHoles is this with one final advance).
class HoleRecognizer {
 public:
  explicit HoleRecognizer(const RecognitionOptions& o = {});
  ~HoleRecognizer();
  HoleRecognizer(HoleRecognizer&&) noexcept;
  HoleRecognizer(const HoleRecognizer&) = delete;
  HoleRecognizer& operator=(const HoleRecognizer&) = delete;
  HoleRecognizer& operator=(HoleRecognizer&&) = delete;

  void advance(const Program& p, bool final);
  /// The program's motions [0, motions) and targets [target_begin, target_end) were dropped
  /// (ProgramStream::retire): the indices after them shift. The holes must have been taken.
  void retired(std::size_t motions, std::size_t target_begin, std::size_t target_end);
  /// The motion the next cycle may start at.
  [[nodiscard]] std::size_t nextMotion() const { return next_; }
  [[nodiscard]] const std::vector<Hole>& holes() const { return holes_; }
  std::vector<Hole> take() { return std::move(holes_); }

 private:
  class PoseCache;  // poses of the motions around the cycle being read, each computed once
  RecognitionOptions o_;
  std::unique_ptr<PoseCache> cache_;
  std::vector<Hole> holes_;
  std::vector<bool> used_;  // targets of recognised cycles
  std::size_t next_{0};     // the motion the next cycle may start at
  std::size_t count_{0};    // holes recognised so far (taken or not): the next id is H<count_ + 1>
};

/// The evidence of a recognised hole of `p` as text, in the order it was found: "feed slower
/// than approach/retract", the drilling markers (dwell, spindle, drill call or comment, as the
/// program writes them), "exact stop at the bottom", "no feed change: surface and depth not known
/// from the program".
std::vector<std::string> holeEvidence(const Program& p, const Hole& h);
/// The one piece of process evidence that made `h` a hole, short (the prediction JSON's
/// "evidence"): "feed segment along the tool axis", else the first spindle/drill call or drilling
/// comment as "MARKER after the motion at line N", else "on the hole list" (a dwell-only cycle a
/// hole list confirmed).
std::string drillingEvidence(const Program& p, const Hole& h);

/// A motion marker that says drilling: starts with DWELL, or contains SPINDLE, DRILL, PLUNGE,
/// BOOR or BOHR (any case).
bool drillMarker(std::string_view marker);

/// A drillMarker that is process evidence on its own: a spindle or drill call or a drilling
/// comment, not a dwell (a gripper dwells at a placement too).
bool processMarker(std::string_view marker);

/// One row of the contract's hole list: `id,x,y,z,i,j,k[,diameter,depth,tolerance,tool,feed,
/// spindle_rpm]` (mm, workobject frame, i,j,k = drilling direction into the material; tool = the
/// controller's tool number or name of the cell's tool table, feed in mm/rev, spindle speed 1/min).
struct HoleSpec {
  std::string id;
  Vec3 position_mm{Vec3::Zero()};
  Vec3 direction{Vec3::UnitZ()};  ///< unit
  std::optional<double> diameter_mm;
  std::optional<double> depth_mm;
  std::optional<double> tolerance_mm;
  std::string tool;  ///< empty: none given
  std::optional<double> feed_mm_per_rev;
  std::optional<double> spindle_rpm;
  int line{0};
};

/// Reads the contract's hole-list CSV; InputError(file, line, msg) on bad rows.
std::vector<HoleSpec> readHoleList(const std::string& path);
std::vector<HoleSpec> parseHoleList(const std::string& path, const std::string& bytes);

struct HoleMatch {
  int hole{-1};             ///< index into the recognised holes
  int spec{-1};             ///< index into the hole list
  double distance_mm{0.0};  ///< distance of the hole-list point from the program's drill line
};

/// Matches recognised holes to a hole list: by id when the ids agree, else by position — the
/// hole-list point within `tol_mm` of the segment entry..bottom (extended by the hole-list
/// depth) with parallel axes (< 1°). Positions compare in the program's frame coordinates,
/// which is the workobject frame when the program's base frame is the workobject.
std::vector<HoleMatch> matchHoles(const std::vector<Hole>& holes, const Program& p,
                                  const std::vector<HoleSpec>& specs, double tol_mm);

/// The holes of `p` with a hole list as evidence: `holes` (recognised without dwell candidates)
/// when they match every hole of the list; else the program recognised again with
/// RecognitionOptions::dwell_candidates, keeping a dwell-only cycle where the list has a hole
/// (matchHoles, `tol_mm`), ids renumbered H1, H2… in program order.
std::vector<Hole> withHoleListEvidence(const Program& p, std::vector<Hole> holes,
                                       const std::vector<HoleSpec>& specs, double tol_mm,
                                       RecognitionOptions o = {});

}  // namespace roprec::postproc
