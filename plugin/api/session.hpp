#pragma once
/// \file session.hpp
/// A cell loaded once for per-target calls from a host: the RoboDK FilterTarget analogue and the
/// predicted deviation at commanded joints. Frames: base = the robot card's base link; poses are
/// the TCP (flange × the cell's tool) in the base frame, SI units.

#include <string>

#include "plugin/api/prediction_setup.hpp"

namespace roprec::api {

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
    HolePrediction before;                 ///< prediction of the wanted pose programmed as is
  };
  /// The pose to program so that the predicted real TCP lands on `T_W_wanted` (base frame, m)
  /// under the cell's gravity, tool and process load; orientation kept. `seed_controller` (rad,
  /// controller convention) picks the IK solution nearest to it; nullptr: the reference pose.
  Filtered filterTarget(const Pose& T_W_wanted, const Vec6* seed_controller = nullptr);

  struct JointPrediction {
    bool ok{false};
    std::string reason;
    Vec3 d_translation{Vec3::Zero()};  ///< δrobot of the TCP, base frame, m
    Vec3 d_rotation{Vec3::Zero()};     ///< rotation vector, base frame, rad
    double U_work{0};  ///< 95 % radius of the anisotropic in-plane distribution (the verdict's), m
    HolePrediction prediction;
  };
  /// The predicted TCP deviation at commanded joints (controller convention, rad).
  JointPrediction predictJoints(const Vec6& joints_controller);

  [[nodiscard]] const PredictionContext& context() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace roprec::api
