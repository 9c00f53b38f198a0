#pragma once
/// \file session.hpp
/// A cell loaded once for per-target calls from a host: the RoboDK FilterTarget analogue, its
/// batch (a whole program's targets, RoboDK's FilterProgram) and the predicted deviation at
/// commanded joints. Frames: base = the robot card's base link; poses are the TCP (flange × the
/// cell's tool) in the base frame, SI units.
///
/// Each call takes the hole's process (HoleProcess: the drill of the cell's tool table and the
/// hole's own diameter, depth, feed and speed, docs/process.md §8, tool table); what it leaves
/// unset is the cell's, and the result states every value used (ProcessUsed). The session keeps its
/// scratch and the processes it has built between calls: a call allocates nothing but its result's
/// texts.

#include <span>
#include <string>
#include <vector>

#include "plugin/api/prediction_setup.hpp"

namespace roprec::api {

/// The process of a host's hole; 0 / empty: the cell's.
struct HoleProcess {
  std::string tool;    ///< the controller's tool number or name (<drill tool>); "": the first drill
  double diameter{0};  ///< m (0: the drill's)
  double depth{0};     ///< m (0: the cell's <cut depth_mm>, else 2 Dc)
  double feed{0};      ///< m/rev (0: the drill's <cut>)
  double spindle_rpm{0};  ///< 1/min (0: the drill's <cut>)
};

/// The process a call used, every value resolved.
struct ProcessUsed {
  std::string tool;       ///< the drill's <drill tool> ("" for a single drill without one)
  std::string drill;      ///< drillLabel: `tool 3 'D6.8' (Ø6.8 mm)`, `the cell's drill (Ø8.5 mm)`
  double diameter{0};     ///< m
  double depth{0};        ///< m
  double feed{0};         ///< m/rev (0: no drilling process)
  double spindle_rpm{0};  ///< 1/min
  bool from_cell{true};   ///< the host gave no value: all of it is the cell's
};

/// A cell loaded once for per-target calls (the RoboDK FilterTarget analogue). Not copyable;
/// not safe for concurrent calls on one session; distinct sessions are independent.
class Session {
 public:
  /// Loads the cell (robot, tool, process, controller). Throws InputError.
  explicit Session(const std::string& cell_path);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  struct Filtered {
    bool ok{false};
    std::string reason;                    ///< why not, when !ok
    Pose T_programmed{Pose::Identity()};   ///< TCP pose to program, base frame (m)
    Vec6 joints_controller{Vec6::Zero()};  ///< programmed joints, controller convention, rad
    std::string config;                    ///< vendor configuration flags of those joints
    double residual{0};                    ///< |predicted real TCP − wanted|, m
    ProcessUsed process;                   ///< what the hole was drilled with
    /// The wanted pose programmed as is: with `with_prediction`, its full prediction (deviation,
    /// budget, verdict); else only the IK choice (joints, branch, flags, status).
    HolePrediction before;
  };
  /// The pose to program so that the predicted real TCP lands on `T_W_wanted` (base frame, m)
  /// under the cell's gravity, tool and the hole's process load; orientation kept (the keep
  /// compensation of this one target, compensateTarget). With a cell <part_registration>
  /// (verify --write-cell) `T_W_wanted` is a pose on the nominal part and is aimed where the
  /// registration found the part (partMotion · T_W_wanted, as compensate aims a program's
  /// holes): `before` and `residual` are then about that registered pose. `seed_controller` (rad,
  /// controller convention) picks the IK solution nearest to it; nullptr: the reference pose.
  /// Throws InputError for a tool the cell's tool table does not have, or a size or feed it
  /// refuses.
  Filtered filterTarget(const Pose& T_W_wanted, const Vec6* seed_controller = nullptr,
                        const HoleProcess& process = {}, bool with_prediction = false);

  /// filterTarget over a program's targets in order (RoboDK's FilterProgram): target i is seeded
  /// with seeds[i] when given (seeds empty or of the targets' size), else with the joints of the
  /// previous filtered target (the first: the reference pose) — the continuity a program has.
  /// processes: empty (the cell's) or one per target.
  std::vector<Filtered> filterTargets(std::span<const Pose> T_W_wanted,
                                      std::span<const Vec6> seeds_controller = {},
                                      std::span<const HoleProcess> processes = {});

  struct JointPrediction {
    bool ok{false};
    std::string reason;
    Vec3 d_translation{Vec3::Zero()};  ///< δrobot of the TCP, base frame, m
    Vec3 d_rotation{Vec3::Zero()};     ///< rotation vector, base frame, rad
    double U_work{0};  ///< 95 % radius of the anisotropic in-plane distribution (the verdict's), m
    ProcessUsed process;
    HolePrediction prediction;
  };
  /// The predicted TCP deviation at commanded joints (controller convention, rad) drilling with
  /// `process`. Throws InputError when a joint is outside the limits (as the CLI, exit 2) or for
  /// a tool the cell's tool table does not have.
  JointPrediction predictJoints(const Vec6& joints_controller, const HoleProcess& process = {});

  [[nodiscard]] const PredictionContext& context() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace roprec::api
