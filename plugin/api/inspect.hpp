#pragma once
/// \file inspect.hpp
/// What a robot program contains (`roprec inspect`; docs/contract.md §11, docs/programs.md):
/// targets (native values, pose in their frame and, where the frame resolves, in the base frame;
/// configuration, external axes, tool/base), motions, recognised drill holes (optionally matched
/// to a hole list), unresolved references and the reader's notes.
///
/// Units: JSON in mm, deg (native values as the program states them).
/// Errors: InputError for an unreadable or malformed program or hole list.

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

/// program, dialect, files, drilling_axis_tcp, targets[], motions[], holes[], unresolved[],
/// notes[].
Json inspectProgram(const InspectRequest& request);

}  // namespace roprec::api
