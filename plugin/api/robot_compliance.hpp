#pragma once
/// \file robot_compliance.hpp
/// Joint compliance of a loaded robot from its card (k, and the servo's static stiffness
/// k_servo = Kv·Kω when both position_gain and velocity_gain are given; otherwise the servo is
/// ideal/integrating, Δψ = 0), and the controller's own gravity compensation if the card says so.
#include "compensator/robot/deflection.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec::api {

/// Throws InputError (card file and line) when the card has no stiffness.
nc::JointCompliance complianceOf(const RobotCard& card);

/// The command offset a gravity-compensating controller adds: K_eff⁻¹ τ_g,cal(θ_m) with the
/// calibration load of the card (zero when the card says gravity_compensated="false").
nc::Vec6 controllerGravityOffset(const Robot& robot, const nc::JointCompliance& c,
                                 const nc::Vec6& theta_m);

}  // namespace roprec::api
