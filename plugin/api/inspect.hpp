#pragma once
/// \file inspect.hpp
/// What a robot program contains (`roprec inspect`; docs/contract.md §11, docs/programs.md):
/// targets (native values, pose in their frame and, where the frame resolves, in the base frame;
/// configuration, external axes, tool/base), motions, recognised drill holes (optionally matched
/// to a hole list), unresolved references and the reader's notes.
///
/// Units: JSON in mm, deg (native values as the program states them).
/// Errors: InputError for an unreadable or malformed program or hole list.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "plugin/api/json.hpp"
#include "plugin/api/program_frames.hpp"

namespace roprec::api {

struct InspectRequest {
  std::string program;  ///< KRL .src, RAPID .mod/.prg/.sys, TP .ls, CSV/JSON targets, hole list
  std::vector<FrameDefinition> frames;   ///< frames the program uses but does not define
  std::optional<Vec3> tool_axis;         ///< drilling axis in the TCP frame (unit); default +z
  std::optional<std::string> hole_list;  ///< hole-list CSV to match the recognised holes to
  double match_tolerance_mm{1.0};        ///< position match of the hole list, mm
};

/// The counts `roprec inspect` prints for a person (the JSON holds everything).
struct InspectSummary {
  std::string program;
  std::string dialect;
  std::size_t files{0};
  std::size_t targets{0};
  std::size_t motions{0};
  std::size_t holes{0};
  std::vector<std::string> unresolved;  ///< "FILE:LINE: REF: what"
  std::vector<std::string> notes;
};

/// program, dialect, files, drilling_axis_tcp, targets[], motions[], holes[], unresolved[],
/// notes[]. With `summary`, also fills its counts.
Json inspectProgram(const InspectRequest& request, InspectSummary* summary = nullptr);

/// A few lines: the program, its dialect and files, how many targets, motions and drill holes,
/// each unresolved reference and note.
std::string inspectSummaryText(const InspectSummary& s);

}  // namespace roprec::api
