#include "compensator/robot/calibration_jacobian.hpp"

namespace roprec {

namespace {

/// The six columns of a frame (rotation R_W_frame, origin o) for the TCP point p.
void frameColumns(const Mat3& R, const Vec3& o, const Vec3& p, int first, CalibrationJacobian& J) {
  for (int k = 0; k < 3; ++k) {
    const Vec3 w = R.col(k);
    J.col(first + k) = w;
    J.col(first + 3 + k) = w.cross(p - o);
  }
}

void frameSigmas(const FrameError& e, int first, CalibrationSigmas& s) {
  s.segment<3>(first) = e.sigma_xyz;
  s.segment<3>(first + 3) = e.sigma_rpy;
}

}  // namespace

void tcpCalibrationJacobian(const ChainDescription& real, const Pose& T_flange_tcp,
                            const Eigen::Matrix<double, 6, 1>& theta, CalibrationJacobian& J) {
  std::array<Pose, 6> joint_frames;
  Pose T = Pose::Identity();
  for (size_t i = 0; i < 6; ++i) {
    const ChainJoint& j = real.joints[i];
    T = T * j.origin;
    joint_frames[i] = T;
    T.rotate(Eigen::AngleAxisd(theta[static_cast<int>(i)], j.axis));
  }
  const Pose T_flange = T * real.tip;
  const Vec3 p = (T_flange * T_flange_tcp).translation();
  frameColumns(Mat3::Identity(), Vec3::Zero(), p, 0, J);
  for (size_t i = 0; i < 6; ++i) {
    frameColumns(joint_frames[i].linear(), joint_frames[i].translation(), p,
                 6 + 6 * static_cast<int>(i), J);
  }
  frameColumns(T_flange.linear(), T_flange.translation(), p, 42, J);
}

CalibrationSigmas calibrationSigmas(const GeometryCalibration& cal) {
  CalibrationSigmas s;
  frameSigmas(cal.base, 0, s);
  for (size_t i = 0; i < 6; ++i) frameSigmas(cal.joints[i], 6 + 6 * static_cast<int>(i), s);
  frameSigmas(cal.tool, 42, s);
  return s;
}

Mat3 calibrationPositionCovariance(const ChainDescription& real, const Pose& T_flange_tcp,
                                   const Eigen::Matrix<double, 6, 1>& theta,
                                   const GeometryCalibration& cal) {
  CalibrationJacobian J;
  tcpCalibrationJacobian(real, T_flange_tcp, theta, J);
  Mat3 C = cal.model_error * cal.model_error * Mat3::Identity();
  if (cal.covariance_parameters.empty()) {
    const CalibrationSigmas s = calibrationSigmas(cal);
    for (int c = 0; c < kCalibrationParameters; ++c) {
      if (s[c] > 0) C += s[c] * s[c] * J.col(c) * J.col(c).transpose();
    }
    return C;
  }
  const auto n = static_cast<Eigen::Index>(cal.covariance_parameters.size());
  Eigen::Matrix<double, 3, Eigen::Dynamic> Jc(3, n);
  for (Eigen::Index k = 0; k < n; ++k)
    Jc.col(k) = J.col(calibrationComponent(cal.covariance_parameters[static_cast<size_t>(k)]));
  return C + Jc * cal.covariance * Jc.transpose();
}

}  // namespace roprec
