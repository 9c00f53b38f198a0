#pragma once
/// \file convert.hpp
/// A program's targets written as a new, minimal program in another dialect (`roprec convert
/// --to`). Carried: every motion with a Cartesian target (pose in its frame, motion type, linear
/// speed, exact stop vs approximation), circular motions with their auxiliary point, the base and
/// tool frames (values where the source resolves them), external axes, and the configuration at
/// the branch level (docs/programs.md §7.1: shoulder, elbow, wrist → KUKA S bits 0–2 with bit 1 =
/// elbow up (§9 item 2 reading), ABB cfx, FANUC F/N U/D T/B).
///
/// Not carried (reported per item, exit code 1): joint targets into another vendor's dialect
/// (joint sign conventions and zeros differ per vendor), targets built at run time.
/// Not carried and listed with their source line (ConversionReport::not_carried, exit code 0):
/// every other instruction (WAIT/WaitTime, I/O, spindle and other calls, control flow) and the
/// zones, which map to one approximation per dialect (KRL C_DIS/C_PTP, RAPID z1, TP CNT100).
/// External axes: RAPID writes 9E+09 for an axis the source does not state (a KRL source's axes
/// that are 0 in every target count as not stated: KRL writes E1..E6 = 0 for absent axes). Turn
/// information is vendor- and joint-convention specific: KUKA T is omitted, ABB cf1/cf4/cf6 are
/// written 0 under `ConfJ\Off`/`ConfL\Off`, FANUC turn digits are written 0 and listed as notes.
/// CSV/JSON keep the source's configuration text and joint values verbatim.
/// Numbers: positions 6 decimals (mm), angles 9 decimals (deg), quaternions 12 decimals, so a
/// conversion keeps poses to < 1e-6 mm and < 1e-9 rad.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "compensator/support/atomic_file.hpp"
#include "postproc/program.hpp"

namespace roprec::postproc {

struct ConversionReport {
  std::vector<std::string> skipped;  ///< items not converted (exit code 1)
  std::vector<std::string> notes;    ///< what the user must check in the output
  /// Into krl/rapid/tp: every source instruction the new program does not carry (waits, I/O,
  /// spindle and other calls, control flow, assignments, interrupts), as "FILE:LINE: text
  /// (kind)" (a repeated instruction once: "(wait; 204 in all, lines 19,28,...)"), and every
  /// zone mapping that changes the source's zone, as "zone z10 -> C_DIS at
  /// FILE:12,14 (2 motions; ...)". Not an error (exit code 0): the motions are all there. Each
  /// notice is at most about kNoticeBytes (its line list cut to ",...") unless convertProgram is
  /// asked for every line.
  std::vector<std::string> not_carried;
  /// When set, each note is handed to it, in order, instead of kept in `notes` (a caller that
  /// groups them holds one line per kind, not one per target of a large program).
  std::function<void(const std::string&)> on_note;
};

/// The length a not-carried notice's line list keeps it to (the count of lines is stated).
inline constexpr std::size_t kNoticeBytes = 1024;

/// The files of the converted program: (path, bytes). KRL: OUT.src and OUT.dat. Throws
/// InputError when a frame the output must state by value is unresolved (give it with --frame).
/// `all_lines`: every line number in the not-carried notices (`--verbose`).
std::vector<std::pair<std::string, std::string>> convertProgram(const Program& p, Dialect to,
                                                                const std::string& out_path,
                                                                ConversionReport& report,
                                                                bool all_lines = false);

/// Receives each file of a converted program, in order: its path and `produce`, which writes
/// the file's bytes through the ByteWriter it is given (piece by piece: a large program is never
/// held whole; writeFileAtomicStream takes these two arguments).
using ConvertedFileSink = std::function<void(
    const std::string& path, const std::function<void(const ByteWriter&)>& produce)>;

/// convertProgram with the files handed to `sink` as they are made (the same bytes, the same
/// report). A frame that must be stated by value but is unresolved throws while its file is
/// being produced.
void convertProgram(const Program& p, Dialect to, const std::string& out_path,
                    ConversionReport& report, bool all_lines, const ConvertedFileSink& sink);

/// Dialect from a `--to` name: krl, rapid, tp, csv, json.
Dialect dialectFromName(const std::string& name);

}  // namespace roprec::postproc
