#pragma once
/// \file plan_test.hpp
/// `roprec plan-test` as a host-facing job: a D-optimal drilling test program for
/// re-identifying the joint stiffness (compensator/precision/identification.hpp planTest), written
/// in the cell's dialect with postproc/drill_program.hpp.
///
/// Frames and units: the region is a box in the cell's **workobject** frame, in **mm**; it holds
/// the candidate **drill points** (hole bottoms: the point the program's drill cycle feeds to). A
/// hole is drilled `depth` deep, so its entry is `depth` before the drill point along the drilling
/// direction. Directions are unit vectors in the workobject frame; ψ (rotation about the drilling
/// axis) in degrees. Inside the structs: SI.
///
/// Errors: bad arguments (region, count, directions) throw UsageError; a bad cell InputError;
/// fewer admissible candidates than `count` InputError("", 0, …) (planTest). Deterministic.

#include <optional>
#include <string>
#include <vector>

#include "compensator/precision/identification.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "postproc/drill_program.hpp"

namespace roprec::api {

struct PlanTestOptions {
  int per_axis{4};  ///< candidate grid points per axis of the region (an axis with lo = hi: 1)
  std::vector<Vec3> directions{Vec3(0, 0, -1)};    ///< drilling directions, workobject frame
  std::vector<double> psi_deg{0.0, 90.0};          ///< rotations about the drilling axis, deg
  Registration registration{Registration::kNone};  ///< nuisance parameters of the criterion
  double sigma_um{5.0};   ///< expected σ per in-plane axis of a residual, µm
  double depth_mm{0};     ///< hole depth, mm (0: the cell's process depth, else 20 mm)
  double diameter_mm{0};  ///< drill, mm (0: the cell's process drill)
  /// Plan for the geometry (joint origins, tip) as well as the joint compliances (default): the
  /// parameters `verify --calibrate` identifies by default.
  bool geometry{true};
};

struct PlanTestResult {
  PredictionContext context;            ///< the cell (no job)
  std::vector<HoleRequest> candidates;  ///< all candidates (ids C0001…)
  TestPlan plan;                        ///< chosen / rejected candidate indices, expected σ
  /// The chosen holes in program (candidate) order, ids V01…; TCP at the entry point,
  /// workobject frame; the configuration of the planned IK solution.
  std::vector<postproc::DrillHole> holes;
  double depth{0};  ///< m
};

/// Plans `count` test holes among the candidates of the region [lo, hi] (mm, workobject frame).
PlanTestResult planTestJob(const std::string& cell_path, const Vec3& region_lo_mm,
                           const Vec3& region_hi_mm, int count,
                           const PlanTestOptions& options = {});

/// A geometry group of a plan (a joint origin or the tip): the largest prior and expected σ of
/// its translation (m) and rotation (rad) components.
struct PlanGroupSigma {
  std::string group;  ///< "joint 1 origin" … "joint 6 origin", "tip"
  double prior_xyz{0}, expected_xyz{0}, prior_rpy{0}, expected_rpy{0};
};
std::vector<PlanGroupSigma> geometryGroups(const TestPlan& plan);

/// The dialect of the cell's robot (KUKA: KRL, ABB: RAPID, FANUC: TP), or a hole list when
/// `out_path` ends in ".csv". UsageError for a generic robot without a hole-list output.
postproc::Dialect planTestDialect(const PlanTestResult& r, const std::string& out_path);

/// The program text: frames and tool from the cell, the program name = the file stem of
/// `out_path` (KRL requires it). Throws UsageError for invalid names/holes.
postproc::DrillProgramText planTestProgram(const PlanTestResult& r, const std::string& out_path);

}  // namespace roprec::api
