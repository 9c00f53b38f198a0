#pragma once
/// \file robot_options.hpp
/// Options several commands share, read here and handed to the API as plain values:
/// - the robot commands': `--robot NAME|robot.xml|file.urdf`, `--base LINK`, `--tip LINK`,
///   `--cell CELL.xml` (the cell's robot and tool are used; `--robot` overrides the cell's robot),
///   `--stiffness "k1 .. k6"` (N m/rad, overrides the card) — loaded by plugin/api/robot_setup.hpp;
/// - the program commands' `--frame 'REF=x y z a b c[;REF=...]'` (plugin/api/program_frames.hpp).

#include <string>
#include <vector>

#include "plugin/api/job.hpp"
#include "plugin/api/program_frames.hpp"
#include "plugin/api/robot_setup.hpp"
#include "plugin/cli/cli.hpp"

namespace roprec::cli {

/// Reads --robot/--base/--tip/--cell/--stiffness from args and loads the robot setup.
RobotSetup loadRobotFromArgs(Args& args);

/// `--frame 'REF=x y z a b c[;REF=...]'` (mm, deg, KUKA ABC) -> frame definitions (SI).
std::vector<FrameDefinition> parseFrames(const std::string& text);

/// predict/compensate: `--frame cell | "x y z a b c" | 'REF=x y z a b c[;REF=...]'` and
/// `--tool program|cell` into `opt`. Throws UsageError for a bad value.
void parseFrameTool(Args& args, JobOptions& opt);

/// The job notes a user must see on stderr, not only in the JSON: the frame/tool resolutions,
/// the `--holes` partial matches and `--force`.
void printJobNotes(CommandContext& ctx, const std::vector<std::string>& notes);

}  // namespace roprec::cli
