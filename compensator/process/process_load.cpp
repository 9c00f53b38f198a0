#include "compensator/process/process_load.hpp"

#include <cstdio>

namespace roprec {

SteadyProcessLoad steadyProcessLoad(const ProcessSpec& spec) {
  SteadyProcessLoad out;
  char buf[256];
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
      std::snprintf(buf, sizeof buf, "drilling Dc %.2f mm, f %.3f mm/rev, %s",
                    d.geometry.diameter * 1e3, d.feed * 1e3,
                    d.material ? d.material->name.c_str() : "calibrated coefficients");
      out.description = buf;
      break;
    }
    case ProcessType::kMilling: {
      const MillingSpec& s = spec.milling;
      const MillingModel m = millingModelOf(s);
      const Vec3 Fm = millingMeanForce(m, s.cut.fz, s.cut.ae);
      // milling frame: X = feed = tool x, Z = tip → spindle = −tool z, Y = Z × X = −tool y
      out.wrench.force = Vec3(Fm.x(), -Fm.y(), -Fm.z());
      std::snprintf(buf, sizeof buf,
                    "milling D %.2f mm, ae %.2f mm, ap %.2f mm, fz %.3f mm (feed along tool x)",
                    s.tool.diameter * 1e3, s.cut.ae * 1e3, s.cut.ap * 1e3, s.cut.fz * 1e3);
      out.description = buf;
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
