#pragma once
/// The part registration the registration tests give a cell, in the cell's text and by hand.

#include <Eigen/Geometry>
#include <string>

#include "compensator/support/rotation.hpp"

namespace roprec::test {

/// `cell_text` with `<part_registration xyz_mm="0.35 -0.2 0.25" rpy_mrad="0.5 -0.4 0.6">` after
/// its <workobject> (an empty string when the cell has none).
inline std::string withPartRegistration(std::string cell_text) {
  const size_t wobj = cell_text.find("<workobject ");
  if (wobj == std::string::npos) return "";
  cell_text.insert(cell_text.find("/>", wobj) + 2,
                   "\n  <part_registration xyz_mm=\"0.35 -0.2 0.25\" rpy_mrad=\"0.5 -0.4 0.6\" "
                   "source=\"test\"/>");
  return cell_text;
}

/// The same registration F by hand (m, rad; URDF rpy: R = Rz · Ry · Rx), in the workobject frame.
inline Pose partRegistration() {
  Pose F = Pose::Identity();
  F.linear() =
      (Eigen::AngleAxisd(0.6e-3, Vec3::UnitZ()) * Eigen::AngleAxisd(-0.4e-3, Vec3::UnitY()) *
       Eigen::AngleAxisd(0.5e-3, Vec3::UnitX()))
          .toRotationMatrix();
  F.translation() = Vec3(0.35e-3, -0.2e-3, 0.25e-3);
  return F;
}

}  // namespace roprec::test
