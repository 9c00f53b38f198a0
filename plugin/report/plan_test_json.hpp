#pragma once
/// \file plan_test_json.hpp
/// The summary JSON of a planned test (plugin/api/plan_test.hpp computes the plan).
///
/// Units: mm, mrad, µm, N·m/rad (σ(k)); relative σ without unit.

#include <string>
#include <vector>

#include "plugin/api/plan_test.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// Summary JSON (C ABI, Python): holes, candidates, rejected, log_det, per joint the prior and
/// expected relative σ and expected σ(k) (N·m/rad), chosen ids, and `written`; with geometry
/// also per geometry group (joint origins, tip) the largest prior and expected σ (mm, mrad), the
/// unobservable parameters, the names of the exactly dependent ones (`dependent`) and the
/// predicted accuracy (µm) before and after calibration.
Json planTestSummaryJson(const PlanTestResult& r, const std::vector<std::string>& written);

}  // namespace roprec::api
