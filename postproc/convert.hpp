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
/// (joint sign conventions and zeros differ per vendor), targets built at run time. Turn
/// information is vendor- and joint-convention specific: KUKA T is omitted, ABB cf1/cf4/cf6 are
/// written 0 under `ConfJ\Off`/`ConfL\Off`, FANUC turn digits are written 0 and listed as notes.
/// CSV/JSON keep the source's configuration text and joint values verbatim.
/// Numbers: positions 6 decimals (mm), angles 9 decimals (deg), quaternions 12 decimals, so a
/// conversion keeps poses to < 1e-6 mm and < 1e-9 rad.

#include <string>
#include <utility>
#include <vector>

#include "postproc/program.hpp"

namespace roprec::postproc {

struct ConversionReport {
  std::vector<std::string> skipped;  ///< items not converted (exit code 1)
  std::vector<std::string> notes;    ///< what the user must check in the output
};

/// The files of the converted program: (path, bytes). KRL: OUT.src and OUT.dat. Throws
/// InputError when a frame the output must state by value is unresolved (give it with --frame).
std::vector<std::pair<std::string, std::string>> convertProgram(const Program& p, Dialect to,
                                                                const std::string& out_path,
                                                                ConversionReport& report);

/// Dialect from a `--to` name: krl, rapid, tp, csv, json.
Dialect dialectFromName(const std::string& name);

}  // namespace roprec::postproc
