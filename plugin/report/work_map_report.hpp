#pragma once
/// \file work_map_report.hpp
/// The outputs of `roprec map` (docs/reports.md §5): the work map (plugin/api/work_map.hpp) as
/// CSV and as a self-contained HTML page of heat maps.

#include <string>

#include "plugin/api/work_map.hpp"

namespace roprec::api {

/// One row per point × feed: feed_mm_per_rev, x_mm, y_mm, z_mm, status, verdict, branch, config,
/// config_change (0/1: differs from the map's most frequent configuration), j1_deg … j6_deg,
/// d_robot_um (|δrobot|), position_error_um (e⊥), U_work_um, U95_um, tolerance_mm, reason,
/// j1_ctrl_deg..j6_ctrl_deg (the joints as the controller shows them; j*_deg are URDF joints).
std::string workMapCsv(const WorkMap& map);

/// Self-contained HTML: one heat map per feed, quantity (|δrobot|, e⊥, U₉₅) and z slice (when
/// the region is 3-D), colour scales shared across feeds, t/2 marked, configuration boundaries
/// drawn, unreachable cells crossed. Deterministic bytes.
std::string workMapReport(const WorkMap& map);

}  // namespace roprec::api
