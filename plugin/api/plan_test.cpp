#include "plugin/api/plan_test.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "compensator/support/error.hpp"

namespace roprec::api {
namespace {

void checkOptions(const Vec3& lo, const Vec3& hi, int count, const PlanTestOptions& o) {
  if (!lo.allFinite() || !hi.allFinite()) throw UsageError("the region must be finite numbers");
  if ((hi - lo).minCoeff() < 0) throw UsageError("the region needs x0 <= x1, y0 <= y1, z0 <= z1");
  if (count < 1) throw UsageError("the hole count must be >= 1");
  if (o.per_axis < 1 || o.per_axis > 50)
    throw UsageError("candidates per axis must lie in [1, 50]");
  if (o.directions.empty() || o.psi_deg.empty())
    throw UsageError("give at least one drilling direction and one rotation");
  for (const Vec3& d : o.directions) {
    if (!d.allFinite() || d.norm() < 1e-9) throw UsageError("a drilling direction is zero");
  }
  if (!(o.sigma_um > 0) || !(o.depth_mm >= 0) || !(o.diameter_mm >= 0))
    throw UsageError("sigma > 0, depth >= 0, diameter >= 0");
}

std::vector<HoleRequest> candidates(const PredictionContext& c, const Vec3& lo, const Vec3& hi,
                                    const PlanTestOptions& o, double diameter) {
  std::vector<Vec3> dirs;
  for (const Vec3& d : o.directions) dirs.push_back(d.normalized());
  std::vector<double> psi;
  for (const double p : o.psi_deg) psi.push_back(p * kDeg);
  std::vector<HoleRequest> cand =
      planningCandidates(c.cell.T_base_wobj, lo * 1e-3, hi * 1e-3, o.per_axis, dirs, psi);
  for (HoleRequest& h : cand) h.diameter = diameter;
  return cand;
}

/// The chosen holes in candidate order, renamed V01…, TCP at the entry, with their configuration.
std::vector<postproc::DrillHole> chosenHoles(const PlanTestResult& r) {
  std::vector<int> chosen = r.plan.chosen;
  std::sort(chosen.begin(), chosen.end());
  PredictionData data(r.context.model);
  const Pose T_wobj_W = r.context.cell.T_base_wobj.inverse();
  const int width = chosen.size() >= 100 ? 3 : 2;
  std::vector<postproc::DrillHole> out;
  const Vec6* seed = nullptr;
  Vec6 prev;
  for (size_t n = 0; n < chosen.size(); ++n) {
    const HoleRequest& q = r.candidates[static_cast<size_t>(chosen[n])];
    const HolePrediction p = predictHole(r.context.model, data, q, seed);
    char id[16];
    std::snprintf(id, sizeof id, "V%0*d", width, static_cast<int>(n) + 1);
    postproc::DrillHole h;
    h.id = id;
    Pose T = T_wobj_W * q.T_W_tcp;
    T.translation() -= r.depth * T.linear().col(2);
    h.T_frame_tcp = T;
    h.depth = r.depth;
    h.diameter = q.diameter;
    if (p.status == HoleStatus::kOk && !p.config.empty()) h.config = p.config;
    if (p.status == HoleStatus::kOk) {
      prev = p.joints;
      seed = &prev;
    }
    out.push_back(h);
  }
  return out;
}

}  // namespace

PlanTestResult planTestJob(const std::string& cell_path, const Vec3& region_lo_mm,
                           const Vec3& region_hi_mm, int count, const PlanTestOptions& options) {
  checkOptions(region_lo_mm, region_hi_mm, count, options);
  PlanTestResult r;
  r.context = loadPredictionContext(cell_path, "", std::nullopt, "", 0.5, false);
  const ProcessAtDiameter* proc = processFor(r.context.model, 0.0);
  const double diameter = options.diameter_mm > 0 ? options.diameter_mm * 1e-3
                          : proc != nullptr       ? proc->diameter
                                                  : 0.0;
  r.depth = options.depth_mm > 0                         ? options.depth_mm * 1e-3
            : proc != nullptr && proc->default_depth > 0 ? proc->default_depth
                                                         : 20e-3;
  r.candidates = candidates(r.context, region_lo_mm, region_hi_mm, options, diameter);
  PlanOptions po;
  po.compliance_prior_rel = compliancePriorSigma(r.context.robot.card);
  po.sigma = options.sigma_um * 1e-6;
  po.registration = options.registration;
  po.T_W_wobj = r.context.cell.T_base_wobj;
  po.geometry = options.geometry;
  r.plan = planTest(r.context.model, r.candidates, count, po);
  r.holes = chosenHoles(r);
  return r;
}

postproc::Dialect planTestDialect(const PlanTestResult& r, const std::string& out_path) {
  const std::string ext = std::filesystem::path(out_path).extension().string();
  if (ext == ".csv") return postproc::Dialect::kHoleCsv;
  switch (r.context.robot.card.vendor) {
    case Vendor::kKuka:
      return postproc::Dialect::kKrl;
    case Vendor::kAbb:
      return postproc::Dialect::kRapid;
    case Vendor::kFanuc:
      return postproc::Dialect::kTp;
    default:
      throw UsageError("the cell's robot has no controller dialect: write a hole list (-o F.csv)");
  }
}

postproc::DrillProgramText planTestProgram(const PlanTestResult& r, const std::string& out_path) {
  postproc::DrillProgramOptions o;
  o.dialect = planTestDialect(r, out_path);
  o.name = std::filesystem::path(out_path).stem().string();
  o.T_base_frame = r.context.cell.T_base_wobj;
  o.T_flange_tcp = r.context.tool.T_flange_tcp;
  o.tool_mass = r.context.tool.mass;
  o.tool_cog = r.context.tool.com;
  o.comment = "roprec plan-test: " + std::to_string(r.holes.size()) +
              (r.plan.names.size() > 6 + 6 ? " D-optimal holes for calibrating the geometry and "
                                             "the joint stiffness"
                                           : " D-optimal holes for re-identifying the joint "
                                             "stiffness");
  std::vector<postproc::DrillHole> holes = r.holes;
  if (o.dialect == postproc::Dialect::kHoleCsv) {
    for (auto& h : holes) h.config.reset();
  }
  try {
    return postproc::writeDrillProgram(holes, o);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

std::vector<PlanGroupSigma> geometryGroups(const TestPlan& plan) {
  std::vector<PlanGroupSigma> out;
  for (int e = 0; e < 7; ++e) {
    const std::string prefix = e < 6 ? "j" + std::to_string(e + 1) + "_" : std::string("tip_");
    PlanGroupSigma g;
    g.group = e < 6 ? "joint " + std::to_string(e + 1) + " origin" : std::string("tip");
    bool any = false;
    for (size_t k = 0; k < plan.names.size(); ++k) {
      if (plan.names[k].rfind(prefix, 0) != 0) continue;
      any = true;
      const bool rot = plan.names[k].find("_r") != std::string::npos;
      const auto i = static_cast<Eigen::Index>(k);
      double& prior = rot ? g.prior_rpy : g.prior_xyz;
      double& expected = rot ? g.expected_rpy : g.expected_xyz;
      prior = std::max(prior, plan.prior_sigma[i]);
      expected = std::max(expected, plan.expected_sigma[i]);
    }
    if (any) out.push_back(g);
  }
  return out;
}

}  // namespace roprec::api
