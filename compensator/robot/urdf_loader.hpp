#pragma once
/// \file urdf_loader.hpp
/// Loads a serial 6R chain from a URDF file with urdfdom (validated first with tinyxml2 so that
/// every error carries the file and the line). Handles rpy origins, negative axes, fixed joints
/// (folded into the neighbouring transforms and inertials), side branches (ignored: e.g. the
/// balancing cylinder and piston of the ABB IRB 6640), and missing <inertial> elements.

#include <string>
#include <vector>

#include "compensator/robot/chain.hpp"

namespace roprec {

struct UrdfChainRequest {
  std::string base_link;  ///< empty: the URDF root link
  std::string
      tip_link;  ///< empty: `tool0`, else `flange`, else the child of the 6th revolute joint
};

/// Throws InputError (file, line, what is wrong) for malformed XML, NaN or missing attributes,
/// loops, unknown link names, prismatic joints, or a chain that is not 6R.
ChainDescription loadUrdfChain(const std::string& path, const UrdfChainRequest& request = {});

/// "" when `I` (kg m², about the centre of mass) is a physical inertia tensor: finite, principal
/// moments >= 0 and satisfying the triangle inequality; else what is wrong (for a message).
std::string inertiaProblem(const Mat3& I);

/// Link names of a URDF in document order (for messages and tools).
std::vector<std::string> urdfLinkNames(const std::string& path);

}  // namespace roprec
