#pragma once
/// \file pose_json.hpp
/// The JSON of a pose that fk, ik, deflect and inspect print.
///
/// Units: position in mm, angles in degrees. Frames: as given (the caller's base frame).

#include "compensator/support/rotation.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// JSON of a pose (base frame): position_mm (6 decimals), quaternion_wxyz (w ≥ 0, 9 decimals) and
/// abc_deg, the KUKA Z-Y'-X'' angles (6 decimals).
Json poseJson(const Pose& T);

/// Sets position_mm (6 decimals) and quaternion_wxyz (w ≥ 0, 9 decimals) of `T` on the object `j`.
void setPositionQuaternion(Json& j, const Pose& T);

}  // namespace roprec::api
