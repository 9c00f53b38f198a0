#include "compensator/process/process_load.hpp"

#include <string>

#include "compensator/support/c_format.hpp"

namespace roprec {

SteadyProcessLoad steadyProcessLoad(const ProcessSpec& spec) {
  SteadyProcessLoad out;
  switch (spec.type) {
    case ProcessType::kWrench:
      out.wrench.force = spec.wrench.force;
      out.wrench.torque = spec.wrench.torque;
      out.description = "measured wrench";
      break;
    case ProcessType::kDrilling: {
      const DrillingSpec& d = spec.drilling;
      const DrillingModel m = drillingModelOf(d);
      const DrillingForces F = drillingForces(m, d.feed);
      ToolWrench w = toolWrench(F, 0.0);
      // The rotating residual Fr has zero mean over a revolution: keep only the steady part.
      w.force.x() = 0.0;
      w.force.y() = 0.0;
      out.wrench = w;
      out.rotating_force = F.residual;
      // "C" format whatever the host's locale (compensator/support/c_format.hpp)
      out.description = "drilling Dc " + cFixed(d.geometry.diameter * 1e3, 2) + " mm, f " +
                        cFixed(d.feed * 1e3, 3) + " mm/rev, " +
                        (d.material ? d.material->name : std::string("calibrated coefficients"));
      break;
    }
    case ProcessType::kMilling: {
      const MillingSpec& s = spec.milling;
      const MillingModel m = millingModelOf(s);
      const Vec3 Fm = millingMeanForce(m, s.cut.fz, s.cut.ae);
      // milling frame: X = feed = tool x, Z = tip → spindle = −tool z, Y = Z × X = −tool y
      out.wrench.force = Vec3(Fm.x(), -Fm.y(), -Fm.z());
      out.description = "milling D " + cFixed(s.tool.diameter * 1e3, 2) + " mm, ae " +
                        cFixed(s.cut.ae * 1e3, 2) + " mm, ap " + cFixed(s.cut.ap * 1e3, 2) +
                        " mm, fz " + cFixed(s.cut.fz * 1e3, 3) + " mm (feed along tool x)";
      break;
    }
  }
  return out;
}

nc::Wrench toBaseFrame(const ToolWrench& w, const Mat3& R_W_tcp) {
  nc::Wrench out;
  out.force = R_W_tcp * w.force;
  out.moment = R_W_tcp * w.torque;
  return out;
}

}  // namespace roprec
