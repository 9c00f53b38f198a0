#pragma once
/// \file measured_poses.hpp
/// Measured robot poses from a laser tracker or a CMM probing a target on the tool — the second
/// input of `roprec verify` / calibration besides drilled holes: a cell with a tracker calibrates
/// without drilling. Reading only; the modelling is compensator/precision/identification.hpp.
///
/// ## The file (CSV, recognised by its header; docs/verification.md)
///   id,j1,j2,j3,j4,j5,j6,x,y,z[,rx,ry,rz][,mass,com_x,com_y,com_z][,fx,fy,fz,mx,my,mz][,u][,u_rot]
///  * `id`: the pose's name (unique).
///  * `j1..j6`: the **commanded** joints the controller was given (degrees, the controller's
///    convention = the card's URDF convention with its vendor offsets removed by the host; roprec
///    takes them as URDF joint values). All six cells empty: the pose is the **program's target**
///    named `id` (`verify --cell C PROGRAM --poses P`): its commanded joints are those roprec
///    predicts for that target of the program (the configuration it states).
///  * `x,y,z`: the measured TCP (the tracker's reflector at the cell's tool TCP), **workobject
///    frame of the cell, mm** (the tracker's frame after its alignment; a residual offset is the
///    registration `verify --register` estimates).
///  * `rx,ry,rz`: optional measured TCP orientation (a 6-DoF tracker probe), degrees, of the
///    cell's tool TCP frame in the workobject frame: URDF rpy = fixed X-Y-Z, R =
///    Rz(rz)·Ry(ry)·Rx(rx) (the CSV targets' `# euler: XYZ_fixed`, docs/programs.md). The three
///    cells together; the identification then has three more equations per pose.
///  * `mass` (kg) and `com_x,com_y,com_z` (mm, flange frame): an optional payload on the flange in
///    addition to the cell's tool, all four cells together.
///  * `fx,fy,fz` (N) and `mx,my,mz` (N·m): an optional wrench applied at the TCP, base frame (e.g.
///    a rope and weight), the six together.
///  * `u`: optional standard measurement uncertainty per axis, µm (> 0).
///  * `u_rot`: optional standard uncertainty per axis of the measured orientation, µrad (> 0;
///    default verify's, 100 µrad).
/// Column names are case-insensitive, in any order; unknown columns are ignored; `#` starts a
/// comment line; blank lines are skipped; optional cells of a row may be empty (their group
/// together). Numbers are parsed locale-independently and must be finite.
///
/// Errors: InputError(file, line, what) for a missing column, a non-number, an incomplete
/// optional group, a non-positive u or mass < 0, a duplicate id, or no pose at all.

#include <optional>
#include <string>
#include <vector>

#include "compensator/support/rotation.hpp"

namespace roprec::postproc {

struct MeasuredPose {
  std::string id;
  Eigen::Matrix<double, 6, 1> joints_deg{Eigen::Matrix<double, 6, 1>::Zero()};  ///< commanded
  bool program_target{false};         ///< j1..j6 empty: the joints of the program's target named id
  Vec3 p_mm{Vec3::Zero()};            ///< measured TCP, workobject frame, mm
  std::optional<Vec3> rpy_deg;        ///< measured TCP orientation, workobject frame
  std::optional<double> payload_kg;   ///< extra payload on the flange
  Vec3 payload_com_mm{Vec3::Zero()};  ///< its centre of mass, flange frame
  std::optional<Vec3> force_n;        ///< wrench at the TCP, base frame (with torque_nm)
  Vec3 torque_nm{Vec3::Zero()};
  std::optional<double> u_um;        ///< standard measurement uncertainty per axis
  std::optional<double> u_rot_urad;  ///< standard uncertainty per axis of the orientation
  int line{0};                       ///< 1-based source line
};

struct MeasuredPoses {
  std::string path;                 ///< for messages
  std::vector<MeasuredPose> poses;  ///< file order, ids unique
};

/// Reads a pose file (see the file comment). Throws InputError ("cannot open file", line 0, when
/// it cannot be read).
MeasuredPoses readMeasuredPoses(const std::string& path);
/// The same from text; `path` names the file in messages.
MeasuredPoses parseMeasuredPoses(const std::string& text, const std::string& path);

/// Is `text` a pose file (its first non-comment line names j1 and x)?
bool looksLikeMeasuredPoses(const std::string& text);

/// Writes poses in the format above ('\n' line ends; 6 decimals for joints, 4 for mm); the
/// optional groups are written when any pose has them. Reads back to the same poses.
std::string writeMeasuredPoses(const std::vector<MeasuredPose>& poses);

}  // namespace roprec::postproc
