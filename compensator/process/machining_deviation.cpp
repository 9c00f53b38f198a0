#include "compensator/process/machining_deviation.hpp"

#include <cmath>

namespace roprec {

const char* distributionName(Distribution d) {
  switch (d) {
    case Distribution::kNormal:
      return "normal";
    case Distribution::kRectangular:
      return "rectangular";
    case Distribution::kTriangular:
      return "triangular";
    case Distribution::kArcsine:
      return "arcsine";
  }
  return "unknown";
}

double standardUncertainty(double half_width, Distribution d) {
  switch (d) {
    case Distribution::kNormal:
      return half_width;
    case Distribution::kRectangular:
      return half_width / std::sqrt(3.0);
    case Distribution::kTriangular:
      return half_width / std::sqrt(6.0);
    case Distribution::kArcsine:
      return half_width / std::sqrt(2.0);
  }
  return half_width;
}

MachiningDeviationParams defaultMachiningDeviation(double diameter, bool carbide) {
  MachiningDeviationParams p;
  const char* band =
      "chosen with the other machining-deviation defaults so that 2 u_c is about +-30 um at "
      "Dc 8 mm and "
      "+-60 um at Dc 12 mm (Ferreras-Higuero et al., RCIM 2020 [P, not confirmed against the paper "
      "text])";
  p.axis_tilt = 0.03 * kDeg;
  p.axis_lever = diameter;
  p.axis_source =
      std::string(
          "estimate: tool-axis deviation 0.03 deg evaluated at a lever of 1 Dc (mid-depth of a "
          "2xDc hole); ") +
      band;
  p.stickout = 3.0 * diameter;
  p.stickout_source = "estimate: stick-out 3 Dc (DIN 6537 short carbide drill, 3xD series)";
  p.runout = 0.25e-3 * p.stickout;
  p.runout_source =
      std::string("estimate: 0.25 um per mm of stick-out (collet angular runout); ") + band;
  p.equivalent_diameter_ratio = 0.8;
  p.youngs_modulus = carbide ? 600e9 : 210e9;
  p.modulus_source = carbide ? "estimate: WC-Co carbide, E 580-630 GPa (handbook range), 600 GPa"
                             : "estimate: HSS, E 210 GPa (handbook value for tool steel)";
  p.spindle_compliance = 0.29e-6;
  p.spindle_source =
      std::string("estimate: spindle + holder lateral compliance 0.29 um/N at the tip; ") + band;
  return p;
}

MachiningDeviation machiningDeviation(const MachiningDeviationParams& p, const DrillGeometry& g,
                                      double rotating_force,
                                      const Eigen::Vector2d& static_force_xy) {
  MachiningDeviation d;
  const double de = p.equivalent_diameter_ratio * g.diameter;
  const double I = kPi * std::pow(de, 4) / 64.0;
  d.tool_compliance = std::pow(p.stickout, 3) / (3.0 * p.youngs_modulus * I) + p.spindle_compliance;
  d.lateral_force = rotating_force;
  d.delta_tool = d.tool_compliance * static_force_xy;

  UncertaintyComponent axis;
  axis.name = "delta_axis";
  axis.half_width = p.axis_lever * std::tan(p.axis_tilt);
  axis.distribution = Distribution::kRectangular;
  axis.source = p.axis_source;
  UncertaintyComponent run;
  run.name = "delta_runout";
  run.half_width = p.runout;
  run.distribution = Distribution::kArcsine;
  run.source = p.runout_source;
  UncertaintyComponent def;
  def.name = "delta_deftool";
  def.half_width = d.tool_compliance * rotating_force;
  def.distribution = Distribution::kArcsine;
  def.source =
      "cantilever L^3/(3 E I_e) + spindle compliance, times the rotating runout force Fr; " +
      p.stickout_source + "; " + p.modulus_source + "; " + p.spindle_source;
  double sum = 0.0;
  for (UncertaintyComponent* c : {&axis, &run, &def}) {
    c->standard = standardUncertainty(c->half_width, c->distribution);
    sum += c->standard * c->standard;
    d.components.push_back(*c);
  }
  d.u_c = std::sqrt(sum);
  d.k = std::sqrt(-2.0 * std::log(0.05));
  d.U = d.k * d.u_c;
  return d;
}

}  // namespace roprec
