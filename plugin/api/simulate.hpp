#pragma once
/// \file simulate.hpp
/// The transient of one process cycle at one pose (flexible joints under the cascade servo,
/// CVODE; compensator/process/transient.hpp, docs/transient.md): the joints of a program's hole,
/// the integration (the CSV time history and the JSON summary `roprec simulate` prints:
/// plugin/report/simulate_output.hpp).
///
/// Units: SI in the structs (s, rad, m, N).
/// Frames: deviations are of the TCP from the nominal rigid TCP, in the base frame.
/// Errors: InputError for bad files and joints outside the limits; HoleUnreachable (an
/// InputError) when the hole exists but no admissible IK solution reaches it. A failed
/// integration is not an error: see transient.ok.

#include <memory>
#include <string>

#include "compensator/process/transient.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

/// The process of the hole a cycle is simulated for (docs/process.md §8, tool table): the drill of
/// the cell's tool table and the hole's own size and cut data; 0 / -1: the cell's.
struct HoleProcessChoice {
  int drill{-1};          ///< index into the tool table (ProcessSpec::drills); -1: the first
  double diameter{0};     ///< m
  double depth{0};        ///< m
  double feed{0};         ///< m/rev
  double spindle_rpm{0};  ///< 1/min
  std::string source;     ///< what said so: "hole list row 3", "program tool TOOL_DATA[2]"
};

/// Joints at which a cycle is simulated, and how they were obtained.
struct HoleJoints {
  nc::Vec6 joints{nc::Vec6::Zero()};  ///< URDF convention, rad
  std::string source;  ///< e.g. "--joints", "target P[3] (cell workobject, configuration ...)"
  HoleProcessChoice process;  ///< the hole's own drill and cut (holeJoints); --joints: the cell's
};

/// The hole is in the program but cannot be reached (an item that cannot be handled, not bad
/// input).
class HoleUnreachable : public InputError {
 public:
  using InputError::InputError;
};

/// Joints of hole `id` of a program (any dialect, incl. the hole-list CSV; needs the setup's
/// cell): the drill point (bottom target) of the recognised hole, its frame from the program when
/// resolved, else the cell's work object; the cell's tool; a joint target as it is; IK with the
/// target's configuration flags when it states them, else the in-limit, non-singular solution
/// nearest the vendor reference pose. A hole-list hole is drilled along its direction with tool x
/// = base x projected ⊥ the axis (else base y). The hole's process: its drill (the program's tool
/// or the row's tool column in the cell's tool table, assignDrill) and the row's diameter, depth,
/// feed and speed, or the program cycle's depth. Throws InputError (no such hole, no pose, a tool
/// the cell does not have) or HoleUnreachable.
HoleJoints holeJoints(const RobotSetup& setup, const std::string& program_path,
                      const std::string& id);

struct SimulateOptions {
  double duration{-1.0};  ///< s; ≤ 0: the process cycle's own duration
  double sample{1e-3};    ///< output sampling, s
  /// CVODE relative tolerance; ≤ 0: the convergence study's default (nc::TransientOptions,
  /// docs/transient.md)
  double rtol{-1.0};
  bool adams{false};    ///< Adams-Moulton instead of the study's BDF (order ≤ 3)
  bool runout{false};   ///< the rotating residual force Fr at spindle frequency
  bool integral{true};  ///< velocity-loop integral action
  bool gravity{true};   ///< link and tool weight (and the controller's gravity compensation)
};

/// The static references (the deflect model: same compliance, load at full engagement; deviation
/// from the same reference as the transient's samples: FK_nom(θ_cmd) for a calibrated card).
struct StaticReference {
  nc::Deflection gravity_only;
  nc::Deflection full_engagement;
};

struct SimulationResult {
  nc::TransientResult transient;  ///< samples; ok/message/t_reached of the integration
  StaticReference static_reference;
  std::string process;         ///< the steady process load, or "none (gravity only)"
  std::string process_source;  ///< drilling at a hole: where its process and drill come from
  nc::ControllerReference controller;       ///< the controller's gravity handling
  nc::DriveModel drive;                     ///< servo, k, B_m, D, Kv, Kω of the run
  std::unique_ptr<nc::ProcessCycle> cycle;  ///< the process cycle integrated
  nc::TransientOptions options;             ///< method, tolerances of the run
  double t_end{0.0};                        ///< s
};

/// Integrates the cell's process cycle (the setup needs a cell; no process: gravity only) with the
/// arm holding `at`; without `duration` the run stops at the end of the cycle (after the retract).
/// Throws UsageError without a cell, InputError outside the joint limits or without stiffness.
SimulationResult simulateAt(const RobotSetup& setup, const HoleJoints& at,
                            const SimulateOptions& options);

}  // namespace roprec::api
