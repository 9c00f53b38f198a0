#pragma once
/// \file drill_program.hpp
/// A new drilling program written from a list of holes, in any dialect (docs/programs.md §14;
/// used by `roprec plan-test`). Every hole becomes the OLP-style drill cycle of the sample jobs
/// (samples/emotor-housing/make_samples.py):
///
///   approach  `approach` above the entry on the drilling axis     joint move (PTP / MoveJ / J)
///   clearance `clearance` above the entry                         linear, rapid speed
///   bottom    `depth` below the entry                             linear, feed speed, exact stop
///   dwell     `dwell` seconds (omitted when 0)
///   retract   back to the approach point                          linear, rapid speed
///
/// TCP +z is the drilling direction (into the material) for every vendor (docs/programs.md §8.2),
/// and all points of a cycle share the hole's orientation. roprec's own readers and drill-cycle
/// recognition (drill.hpp) read the written program back as one hole per DrillHole, in order.
///
/// Numbers (written with formatLike, so the readers' number rules apply): positions 6 decimals
/// (mm), KUKA A,B,C 9 decimals (deg), quaternions 12 decimals, FANUC X..R 6 decimals (mm, deg,
/// the style FANUC loaders are known to accept, docs/programs.md §4.8), hole-list i,j,k 9
/// decimals. Read back, every point is within 5e-7 mm of the input (per component).
///
/// Names: KRL and RAPID points are named after the hole id — the bottom (drill point) is the id
/// itself, the approach `<id>_APP`, the clearance `<id>_CLR` — when the id is a valid identifier
/// of the dialect (letter first, then letters, digits, `_`; KRL ≤ 20, RAPID ≤ 28 characters, not
/// a keyword); otherwise `H<n>` (n = 1-based hole index) and the id stays in the cycle's comment.
/// So matchHoles() pairs a hole list with the program by id. FANUC TP numbers its records
/// (P[3n-2] approach, P[3n-1] clearance, P[3n] bottom); CSV/JSON rows keep the id verbatim
/// (`<id>_APP`, `<id>_CLR`, `<id>`, `<id>_RET`). Name clashes get a `_2`, `_3`… suffix.
///
/// Frames: KRL states `$BASE`/`$TOOL` by value, RAPID a `wobjdata` (uframe = T_base_frame,
/// oframe identity) and a `tooldata`, CSV/JSON `frame`/`tool` declarations. FANUC keeps frames in
/// the controller: the program selects `UFRAME_NUM`/`UTOOL_NUM` and lists the values in remarks
/// (set them on the controller). The hole list carries neither, nor the rotation about the
/// drilling axis (its readers rebuild it, docs/programs.md §0.2).
///
/// Configuration (DrillHole::config, vendor text of the dialect): KRL `S 2 T 35` or
/// `S 'B010' T 'B100011'` (written as given, on every point of the cycle; omitted when absent);
/// RAPID `[cf1,cf4,cf6,cfx]` (absent: `[0,0,0,0]` under `ConfJ \Off`); FANUC `N U T, 0, 0, 0`
/// (absent: `F U T, 0, 0, 0`, listed in the notes); CSV/JSON any text, verbatim. A configuration
/// of another vendor is refused.
///
/// The output is deterministic (byte-identical for identical input). Invalid input throws
/// std::invalid_argument naming the hole or option.

#include <optional>
#include <string>
#include <vector>

#include "postproc/program.hpp"

namespace roprec::postproc {

struct DrillHole {
  std::string id;  ///< unique, non-empty, printable, no `"`, no leading/trailing blank
  Pose T_frame_tcp{Pose::Identity()};  ///< TCP at the entry (surface) point, program frame (SI); z
                                       ///< = drilling direction
  double depth{0.0};                   ///< m, > 0
  double diameter{0.0};                ///< m, informational (comments, hole list)
  std::optional<std::string>
      config;  ///< vendor configuration text of the dialect (see the file comment)
};

struct DrillProgramOptions {
  std::string name{
      "drill"};  ///< program / module name (sanitised to the dialect's identifier rules)
  Dialect dialect{Dialect::kKrl};
  Pose T_base_frame{Pose::Identity()};  ///< program frame (workobject) in the robot base frame (SI)
  Pose T_flange_tcp{Pose::Identity()};  ///< the tool (SI)
  std::string frame_name{"wDrill"};     ///< RAPID wobjdata / CSV, JSON frame name (an identifier)
  std::string tool_name{"tDrill"};      ///< RAPID tooldata / CSV, JSON tool name (an identifier)
  int uframe{1};                        ///< FANUC UFRAME number (1..9)
  int utool{1};                         ///< FANUC UTOOL number (1..10)
  double tool_mass{-1.0};       ///< kg, RAPID tload; <= 0: placeholder 1 kg (listed in the notes)
  Vec3 tool_cog{Vec3::Zero()};  ///< m, tool centre of gravity in the flange frame (RAPID tload)
  double approach{0.05};        ///< m above the entry, > clearance
  double clearance{0.002};      ///< m above the entry, >= 0
  double feed{0.02};            ///< m/s, > 0
  double rapid{0.25};           ///< m/s, > feed (the slower feed is how the cycle is recognised)
  double dwell{0.5};            ///< s at the bottom, >= 0 (0: no dwell instruction)
  std::string comment;          ///< one line, written as a comment / header
  bool crlf{false};             ///< CR LF line ends (KRC and FANUC controller style) instead of LF
};

struct DrillProgramFile {
  std::string suffix;  ///< `.src`, `.dat`, `.mod`, `.ls`, `.csv`, `.json`
  std::string text;
};

struct DrillProgramText {
  Dialect dialect{Dialect::kKrl};
  std::string name;  ///< the program name as written (KRL: must be the file stem)
  std::vector<DrillProgramFile> files;  ///< KRL: [.src, .dat]; others: one file
  std::vector<std::string>
      notes;  ///< what the user must check (frames to set, placeholders, rounding)
};

/// The drilling program for `holes` (see the file comment). Throws std::invalid_argument on
/// invalid holes or options.
DrillProgramText writeDrillProgram(const std::vector<DrillHole>& holes,
                                   const DrillProgramOptions& o);

/// The paths saveDrillProgram(t, out_path) writes: the main file at `out_path` (the suffix is
/// appended when `out_path` has no extension), the others (KRL `.dat`) beside it with the same
/// stem.
std::vector<std::string> drillProgramPaths(const DrillProgramText& t, const std::string& out_path);
/// Writes the files atomically; returns their paths. KRL: throws std::invalid_argument when the
/// file stem differs (ignoring case) from the DEF name, which the controller requires.
std::vector<std::string> saveDrillProgram(const DrillProgramText& t, const std::string& out_path);

/// Reads the written program back with roprec's own reader (parseProgram), as if from
/// `dir`/name + suffix.
Program parseDrillProgram(const DrillProgramText& t, const std::string& dir = ".");

}  // namespace roprec::postproc
