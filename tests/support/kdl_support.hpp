#pragma once
/// KDL reference chains built by kdl_parser from the same URDF file (tests and benchmarks only).
#include <kdl/chain.hpp>
#include <kdl/frames.hpp>
#include <string>

#include "compensator/support/rotation.hpp"

namespace roprec::test {

/// Chain base -> tip from the URDF; `extra` is appended as a fixed segment (e.g. a tool).
/// Fails the current test (ADD_FAILURE) and returns an empty chain when kdl_parser refuses.
KDL::Chain kdlChain(const std::string& urdf, const std::string& base, const std::string& tip,
                    const Pose& extra = Pose::Identity());

KDL::Frame toKdl(const Pose& T);
Pose fromKdl(const KDL::Frame& F);

}  // namespace roprec::test
