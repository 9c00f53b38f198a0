#pragma once
/// \file simulate.hpp
/// The transient of one process cycle at one pose (flexible joints under the cascade servo,
/// CVODE; compensator/process/transient.hpp, docs/transient.md): the joints of a program's hole,
/// the integration, the CSV time history and the JSON summary `roprec simulate` prints.
///
/// Units: SI in the structs (s, rad, m, N); CSV and JSON in s, mm, µm, µrad, N, N·m, deg.
/// Frames: deviations are of the TCP from the nominal rigid TCP, in the base frame.
/// Errors: InputError for bad files and joints outside the limits; HoleUnreachable (an
/// InputError) when the hole exists but no admissible IK solution reaches it. A failed
/// integration is not an error: see transient.ok.

#include <string>

#include "compensator/process/transient.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/json.hpp"
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

struct SimulationResult {
  nc::TransientResult transient;  ///< samples; ok/message/t_reached of the integration
  /// robot, cell, joints_deg, joints_source, process, drive (servo, k, B_m, D, Kv, Kω), static
  /// (gravity-only and full-engagement deviation, as deflect: from FK_nom(θ_cmd) for a calibrated
  /// card, as the transient's samples), transient (end of full engagement,
  /// maxima; drilling: first contact, end of cut, max thrust, cut depth; settling to 0.1 µm with
  /// the equivalent damping ratio; damping: the joint damping ratio, an estimate), cvode (ok,
  /// method, tolerances, statistics, events).
  Json summary;
};

/// Integrates the cell's process cycle (the setup needs a cell; no process: gravity only) with the
/// arm holding `at`; without `duration` the run stops at the end of the cycle (after the retract).
/// Throws UsageError without a cell, InputError outside the joint limits or without stiffness.
SimulationResult simulateAt(const RobotSetup& setup, const HoleJoints& at,
                            const SimulateOptions& options);

/// CSV: t_s, depth_mm (commanded spindle depth p_c ≥ 0), Fa_N, Ft_N, M_Nm, Fr_N, dx/dy/dz_um,
/// rx/ry/rz_urad, dq1..dq6_urad (link angle − the first sample's command), tip_mm (s = p_c + u),
/// cut_depth_mm (D), feed_per_rev_mm (h = Ḋ·60/n), axial_um (u), phase (docs/transient.md).
std::string transientHistoryCsv(const nc::TransientResult& r);

}  // namespace roprec::api
