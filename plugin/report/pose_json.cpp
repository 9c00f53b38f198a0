/// The JSON of a pose (plugin/report/pose_json.hpp).
#include "plugin/report/pose_json.hpp"

namespace roprec::api {

void setPositionQuaternion(Json& j, const Pose& T) {
  j.set("position_mm", Json::vector(T.translation() * 1e3, 6));
  const Eigen::Quaterniond q = quaternionFromRotation(T.linear());
  j.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
}

Json poseJson(const Pose& T) {
  Json j = Json::object();
  setPositionQuaternion(j, T);
  j.set("abc_deg", Json::vector(zyxFromRotation(T.linear()) / kDeg, 6));
  return j;
}

}  // namespace roprec::api
