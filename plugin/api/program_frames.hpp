#pragma once
/// \file program_frames.hpp
/// Frames a robot program refers to but does not define (e.g. `UFRAME[1]` of a FANUC TP
/// program), given by the caller, and the program read with them resolved. Shared by
/// inspect.hpp and convert.hpp.
///
/// Units: poses in m (SI), in the robot base frame.

#include <string>
#include <vector>

#include "compensator/support/rotation.hpp"
#include "postproc/program.hpp"

namespace roprec::api {

struct FrameDefinition {
  std::string ref;              ///< the program's name for it, e.g. "UFRAME[1]", "UTOOL[1]"
  Pose pose{Pose::Identity()};  ///< m
};

/// Reads the program (any dialect) and defines `frames` in it (postproc::resolveFrame).
/// Throws InputError for an unreadable or malformed program.
postproc::Program readProgramWithFrames(const std::string& path,
                                        const std::vector<FrameDefinition>& frames);

}  // namespace roprec::api
