#pragma once
/// \file simulate_output.hpp
/// What `roprec simulate` writes (plugin/api/simulate.hpp computes it): the JSON summary and the
/// CSV time history of the transient.
///
/// Units: s, mm, µm, µrad, N, N·m, deg. Frames: deviations are of the TCP from the nominal rigid
/// TCP, in the base frame.

#include <string>

#include "plugin/api/simulate.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// robot, cell, joints_deg, joints_source, process, drive (servo, k, B_m, D, Kv, Kω), static
/// (gravity-only and full-engagement deviation, as deflect), transient (end of full engagement,
/// maxima; drilling: first contact, end of cut, max thrust, cut depth; settling to 0.1 µm with
/// the equivalent damping ratio; damping: the joint damping ratio, an estimate), cvode (ok,
/// method, tolerances, statistics, events).
Json simulationSummaryJson(const RobotSetup& setup, const HoleJoints& at,
                           const SimulationResult& r);

/// CSV: t_s, depth_mm (commanded spindle depth p_c ≥ 0), Fa_N, Ft_N, M_Nm, Fr_N, dx/dy/dz_um,
/// rx/ry/rz_urad, dq1..dq6_urad (link angle − the first sample's command), tip_mm (s = p_c + u),
/// cut_depth_mm (D), feed_per_rev_mm (h = Ḋ·60/n), axial_um (u), phase (docs/transient.md).
std::string transientHistoryCsv(const nc::TransientResult& r);

}  // namespace roprec::api
