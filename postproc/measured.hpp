#pragma once
/// \file measured.hpp
/// Measured holes from a coordinate-measuring machine (CMM), for `roprec verify`:
/// readers for three formats recognised by content, writers for each, and the matching of the
/// measured holes to a program's holes.
///
/// Frame and units: every position is a hole position in the **workobject frame**, in **mm**
/// (DMIS files may declare other length units, converted to mm on reading). The optional axis is
/// the measured hole axis (a unit vector after reading; the sign is kept as written). The optional
/// `u` is the standard measurement uncertainty of the position per axis, in **µm**.
///
/// Formats (recognised by content, not by the file name):
///  * **roprec CSV** (the minimal format): a header row naming the columns `id,x,y,z` and
///    optionally `i,j,k` (measured axis) and `u` (µm), in any order; column names are
///    case-insensitive, unknown columns are ignored. `#` starts a comment line; blank lines are
///    skipped. Optional cells may be empty (the three axis cells together).
///  * **PC-DMIS-style CSV**: a header row with the columns `TYPE,NAME,X,Y,Z` and optionally
///    `I,J,K` and `D`/`DIAM`/`DIAMETER` (other columns are ignored); NAME is the hole id. Lines
///    before the header (part name, date) are skipped, and so are rows whose TYPE is not a
///    hole-like feature (one containing CIRC, CYL, HOLE or POINT, or empty): datum planes, lines.
///  * **DMIS output** (`.dmo`): statements `F(id)=FEAT/CIRCLE,INNER,CART,x,y,z,i,j,k,diam` (nominal
///    form) and `FA(id)=FEAT/CIRCLE,INNER,CART,…` (actual form); `FEAT/CYLNDR` is read the same
///    way. When a file holds `FA(...)` statements, those (the measured actuals) are the holes and
///    `F(...)` statements (the nominals) are ignored; otherwise the `F(...)` statements are the
///    holes. `OUTER` features (bosses), other feature types and all other statements are
///    skipped. `$$` starts a comment, a trailing `$` continues a statement on the next line,
///    `UNITS/MM|CM|METER|INCH|FEET` sets the length unit. A diameter ≤ 0 means "not given".
///
/// Numbers are parsed locale-independently (std::from_chars) and must be finite.
/// Errors: every reader throws roprec::InputError(file, line, message) — the line of the
/// offending row or statement — for a missing column, a non-number, a non-finite value, a zero
/// axis, a negative uncertainty, a duplicate id, or a file of none of the three formats.

#include <optional>
#include <string>
#include <vector>

#include "compensator/support/rotation.hpp"

namespace roprec::postproc {

enum class MeasuredFormat { kCsv, kPcDmis, kDmis };
/// "csv", "pc-dmis", "dmis".
const char* measuredFormatName(MeasuredFormat f);

struct MeasuredHole {
  std::string id;
  Vec3 p_mm{Vec3::Zero()};            ///< hole position, workobject frame, mm
  std::optional<Vec3> axis;           ///< measured hole axis, workobject frame, unit vector
  std::optional<double> u_um;         ///< standard measurement uncertainty per axis, µm
  std::optional<double> diameter_mm;  ///< measured diameter, mm (PC-DMIS, DMIS)
  int line{0};                        ///< 1-based source line (first line of a DMIS statement)
};

struct MeasuredHoles {
  std::string path;  ///< for messages
  MeasuredFormat format{MeasuredFormat::kCsv};
  std::vector<MeasuredHole> holes;  ///< in file order, ids unique
};

/// Reads a measured-hole file (format by content). Throws InputError (see the file comment;
/// "cannot open file" with line 0 when it cannot be read).
MeasuredHoles readMeasured(const std::string& path);
/// The same from text; `path` is used in messages only.
MeasuredHoles parseMeasured(const std::string& text, const std::string& path);

/// The format of `text`, or nullopt when it is none of the three: DMIS when a line holds an
/// `F(…)=FEAT/` or `FA(…)=FEAT/` statement; PC-DMIS when the first CSV header row names TYPE and
/// NAME; roprec CSV when it names id.
std::optional<MeasuredFormat> detectMeasuredFormat(const std::string& text);

struct MeasuredWriteOptions {
  int decimals{4};  ///< digits after the decimal point of coordinates (mm); axes get 9
};

/// Writers (text; '\n' line ends). Each reads back to the same holes (coordinates to the printed
/// decimals), except what a format cannot carry: PC-DMIS and DMIS have no `u`, the roprec CSV
/// has no diameter. DMIS writes `FA(id)=FEAT/CIRCLE,INNER,CART,…` statements and needs an axis
/// for every hole: throws std::invalid_argument naming the first hole without one.
std::string writeMeasuredCsv(const std::vector<MeasuredHole>& holes,
                             const MeasuredWriteOptions& o = {});
std::string writeMeasuredPcDmis(const std::vector<MeasuredHole>& holes,
                                const MeasuredWriteOptions& o = {});
std::string writeMeasuredDmis(const std::vector<MeasuredHole>& holes,
                              const MeasuredWriteOptions& o = {});
std::string writeMeasured(const std::vector<MeasuredHole>& holes, MeasuredFormat format,
                          const MeasuredWriteOptions& o = {});

/// A program hole to match against: its id and nominal position (workobject frame, mm).
struct ProgramHoleRef {
  std::string id;
  Vec3 p_mm{Vec3::Zero()};
};

/// Measured holes matched to a program's holes by id.
struct MeasuredMatch {
  std::vector<int>
      measured_of_program;      ///< per program hole: index into MeasuredHoles::holes, or −1
  std::vector<int> unknown;     ///< measured holes whose id no program hole has
  std::vector<int> unmeasured;  ///< program holes never measured
  int matched{0};
};

/// Matches by id (exact, case-sensitive; a program id that occurs twice matches its first hole,
/// the later ones count as unmeasured). Reports unknown ids and unmeasured holes in the result.
///
/// Refuses a file that looks like metres: every measured coordinate |c| < 5 while two program
/// holes are ≥ 10 mm apart — and the matched holes read as mm are not within 1 mm (RMS) of their
/// nominal positions (which keeps a small part near the workobject origin legal). Throws
/// InputError(measured.path, line of the first measured hole, reason) then, and also when no
/// measured hole matches a program hole.
MeasuredMatch matchMeasured(const MeasuredHoles& measured,
                            const std::vector<ProgramHoleRef>& program);

}  // namespace roprec::postproc
