/// The summary JSON of a planned test (plugin/report/plan_test_json.hpp).
#include "plugin/report/plan_test_json.hpp"

#include <cstdint>

namespace roprec::api {

namespace {

Json stringArray(const std::vector<std::string>& v) {
  Json a = Json::array();
  for (const auto& s : v) a.push(Json::str(s));
  return a;
}

/// The geometry part of the plan summary (absent for a stiffness-only plan).
void setGeometryJson(Json& j, const PlanTestResult& r) {
  const std::vector<PlanGroupSigma> groups = geometryGroups(r.plan);
  if (groups.empty()) return;
  Json a = Json::array();
  for (const PlanGroupSigma& g : groups) {
    Json o = Json::object();
    o.set("group", Json::str(g.group));
    o.set("prior_sigma_mm", Json::number(g.prior_xyz * 1e3, 4));
    o.set("expected_sigma_mm", Json::number(g.expected_xyz * 1e3, 4));
    o.set("prior_sigma_mrad", Json::number(g.prior_rpy * 1e3, 4));
    o.set("expected_sigma_mrad", Json::number(g.expected_rpy * 1e3, 4));
    a.push(o);
  }
  j.set("geometry", a);
  j.set("unobservable", stringArray(r.plan.unobservable));
  // the names only (the combinations are printed by the CLI): the summary stays short
  std::vector<std::string> dependent;
  for (const std::string& d : r.plan.dependencies) dependent.push_back(d.substr(0, d.find(' ')));
  j.set("dependent", stringArray(dependent));
  j.set("prior_accuracy_um", Json::number(r.plan.prior_accuracy * 1e6, 2));
  j.set("predicted_accuracy_um", Json::number(r.plan.predicted_accuracy * 1e6, 2));
}

}  // namespace

Json planTestSummaryJson(const PlanTestResult& r, const std::vector<std::string>& written) {
  Json j = Json::object();
  j.set("holes", Json::integer(static_cast<std::int64_t>(r.holes.size())));
  j.set("candidates", Json::integer(static_cast<std::int64_t>(r.candidates.size())));
  j.set("rejected", Json::integer(static_cast<std::int64_t>(r.plan.rejected.size())));
  j.set("log_det", Json::number(r.plan.log_det, 6));
  Json joints = Json::array();
  for (int k = 0; k < 6; ++k) {
    Json o = Json::object();
    o.set("joint", Json::integer(k + 1));
    o.set("k_card",
          Json::number(r.context.robot.card.joints[static_cast<size_t>(k)].stiffness, -1));
    o.set("prior_sigma_rel", Json::number(r.plan.prior_sigma_rel[k], 6));
    o.set("expected_sigma_rel", Json::number(r.plan.expected_sigma_rel[k], 6));
    o.set("expected_sigma_k", Json::number(r.plan.expected_sigma_k[k], 1));
    joints.push(o);
  }
  j.set("joints", joints);
  Json ids = Json::array();
  for (const auto& h : r.holes) ids.push(Json::str(h.id));
  j.set("ids", ids);
  setGeometryJson(j, r);
  Json w = Json::array();
  for (const auto& p : written) w.push(Json::str(p));
  j.set("written", w);
  return j;
}

}  // namespace roprec::api
