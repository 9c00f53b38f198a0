#pragma once
/// \file milling_output.hpp
/// What `roprec milling-stability` writes (plugin/api/milling_stability.hpp computes it) and the
/// "dynamics"/"stability" blocks of `roprec forces`: the modes, the zero-order chatter limit, the
/// lobe diagram as CSV and as a self-contained HTML page.
///
/// Units: mm, Hz, rpm, N/µm, µm/N. Frames: the milling frame (X = feed, Y, Z from the tool tip
/// toward the spindle).

#include <string>

#include "compensator/compensation/milling_compensation.hpp"
#include "plugin/api/milling_stability.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// "dynamics": the modes (frequency, damping, TCP direction and stiffness, joint shape), the tooth
/// frequency and the modal model's static compliance; `robot` says whether robot modes are in it.
Json millingDynamicsJson(const ModalModel& dyn, const MillingSpec& s, bool robot);
/// "stability": Kt, Kr, α and the zero-order limit at the cut's spindle speed (margin = ap_lim/ap).
Json millingStabilityJson(const ModalModel& dyn, const MillingModel& m);

/// A path point's chatter check (PathPointCompensation): checked, bounded, ap_limit_mm,
/// chatter_frequency_Hz, margin (limit/ap), stable (by both mechanisms), first_mode_Hz and the
/// "mode_coupling" block.
Json pathPointStabilityJson(const PathPointCompensation& p, double ap);
/// Its "mode_coupling" block (milling_mode_coupling.hpp): bounded, ap_limit_mm, frequency_Hz,
/// kind (flutter | divergence), margin (limit/ap), stable.
Json pathPointModeCouplingJson(const PathPointCompensation& p, double ap);

struct MillingStabilityOutput {
  Json json;           ///< cell, joints_deg, dynamics, stability, lobes summary
  std::string csv;     ///< spindle_rpm,ap_limit_mm,chatter_Hz,lobe (ap empty when unbounded)
  std::string report;  ///< HTML: the lobe diagram with the programmed cut marked
};

MillingStabilityOutput millingStabilityOutput(const MillingStabilityResult& r);

}  // namespace roprec::api
