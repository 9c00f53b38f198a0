#pragma once
/// \file inspect.hpp
/// What a robot program contains (`roprec inspect`; docs/contract.md §11, docs/programs.md):
/// targets (native values, pose in their frame and, where the frame resolves, in the base frame;
/// configuration, external axes, tool/base), motions, recognised drill holes (optionally matched
/// to a hole list), unresolved references and the reader's notes.
///
/// Units: SI in the structs (the JSON, in mm and deg: plugin/report/inspect_output.hpp).
/// Errors: InputError for an unreadable or malformed program or hole list.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "plugin/api/program_frames.hpp"
#include "postproc/drill.hpp"

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

/// A hole list matched to the recognised holes (InspectRequest::hole_list).
struct HoleListMatch {
  std::vector<postproc::HoleSpec> specs;
  std::vector<postproc::HoleMatch> matches;
};

/// What inspect found: the program as read (with the given frames), the recognised holes and
/// the hole-list matches.
struct InspectedProgram {
  std::string path;  ///< the program as requested
  postproc::Program program;
  Vec3 tool_axis{Vec3::UnitZ()};  ///< the drilling axis in the TCP frame used
  std::vector<postproc::Hole> holes;
  HoleListMatch list;
};

/// Reads the program, recognises its drill holes and matches them to the hole list.
InspectedProgram inspectProgram(const InspectRequest& request);

/// The counts of `r` for a person.
InspectSummary inspectSummary(const InspectedProgram& r);

}  // namespace roprec::api
