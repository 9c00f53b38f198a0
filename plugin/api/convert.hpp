#pragma once
/// \file convert.hpp
/// A robot program through its own reader and writer (byte-identical when nothing changed), or
/// its Cartesian targets into a new, minimal program in another dialect (`roprec convert`;
/// docs/programs.md). Configuration is carried at the branch level; joint targets go only into
/// csv/json.
///
/// Errors: InputError for an unreadable program, an unknown dialect name or a frame the output
/// must state by value but that is unresolved (define it in `frames`). Items that cannot be
/// converted are listed in `skipped`, not thrown.

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "plugin/api/program_frames.hpp"

namespace roprec::api {

struct ConvertRequest {
  std::string program;            ///< the source program (any dialect)
  std::string output;             ///< the output path (KRL: the .src; the .dat goes beside it)
  std::optional<std::string> to;  ///< krl, rapid, tp, csv or json; none: the program's own writer
  std::vector<FrameDefinition> frames;  ///< frames the program uses but does not define
  /// Every line number in the not-carried notices (else each notice is cut to about 1 KB).
  bool all_lines{false};
};

struct ConvertResult {
  std::vector<std::string> written;  ///< the paths written
  std::vector<std::string> notes;  ///< what to check in the output, one line per kind (groupNotes)
  std::vector<std::string> skipped;  ///< items not converted
  /// source instructions and zones the new program does not carry ("FILE:LINE: text (kind)",
  /// "zone z10 -> C_DIS at FILE:12,14 (...)"); postproc::ConversionReport::not_carried
  std::vector<std::string> not_carried;
};

/// Reads, converts and writes (atomically) the program.
ConvertResult convertProgramFile(const ConvertRequest& request);

/// The converter's notes ("p7: no configuration in the source; ...", repeated per target), each
/// message once with the targets it concerns (the first three named), in first-seen order:
/// "p7: message" for one target, "message (12 items: p1, p2, p3, ...)" for several.
std::vector<std::string> groupNotes(const std::vector<std::string>& notes);

/// groupNotes kept as the notes come: one entry per message (its count and first three
/// targets), not one per note.
class NoteGroups {
 public:
  void add(const std::string& note);
  /// groupNotes(every note added).
  [[nodiscard]] std::vector<std::string> lines() const;

 private:
  struct Group {
    std::size_t count{0};
    std::vector<std::string> names;  ///< the first three
  };
  std::vector<std::string> order_;  ///< messages in first-seen order
  std::unordered_map<std::string, Group> groups_;
};

}  // namespace roprec::api
