/// The listing of robot cards (plugin/report/robots_output.hpp).
#include "plugin/report/robots_output.hpp"

#include <iomanip>
#include <locale>
#include <sstream>

namespace roprec::api {

namespace {
const char* stiffnessOrigin(const RobotCard& card) {
  int estimated = 0;
  for (const JointCard& j : card.joints) estimated += j.estimated() ? 1 : 0;
  return estimated == 6 ? "ESTIMATE" : estimated ? "partly estimated" : "published";
}
}  // namespace

Json robotCardJson(const RobotCard& card) {
  Json r = Json::object();
  r.set("name", Json::str(card.name));
  r.set("vendor", Json::str(vendorName(card.vendor)));
  r.set("model", Json::str(card.model));
  r.set("urdf", Json::str(card.urdf_path.substr(card.urdf_path.find_last_of('/') + 1)));
  r.set("rated_payload_kg", Json::number(card.rated_payload_kg, 1));
  r.set("repeatability_rp_mm", Json::number(card.rp_mm, 3));
  r.set("repeatability_source", Json::str(card.rp_source));
  r.set("dimensions_source", Json::str(card.dimensions_source));
  r.set("inertial_source", Json::str(card.inertial_source));
  Json joints = Json::array();
  for (const JointCard& j : card.joints) {
    Json jj = Json::object();
    jj.set("name", Json::str(j.name));
    jj.set("stiffness_Nm_per_rad", Json::number(j.stiffness, 0));
    jj.set("estimate", Json::boolean(j.estimated()));
    jj.set("source", Json::str(j.source));
    if (j.position_gain) jj.set("position_gain_per_s", Json::number(*j.position_gain, 3));
    joints.push(jj);
  }
  r.set("joints", joints);
  r.set("gravity_compensated", Json::boolean(card.gravity_compensated));
  return r;
}

std::string robotCardText(const RobotCard& card) {
  std::ostringstream text;
  text.imbue(std::locale::classic());  // "C" numbers whatever the host's global locale
  text << card.name << "  (" << vendorName(card.vendor) << " " << card.model << ")\n";
  text << "  repeatability RP " << std::fixed << std::setprecision(3) << card.rp_mm
       << " mm (ISO 9283)  [" << card.rp_source << "]\n";
  text << "  stiffness k1..k6 [N m/rad]:";
  for (const JointCard& j : card.joints)
    text << " " << std::scientific << std::setprecision(2) << j.stiffness;
  text << std::fixed << "\n";
  text << "  stiffness source: " << stiffnessOrigin(card) << " — " << card.joints[0].source << "\n";
  text << "  inertials: " << card.inertial_source << "\n";
  text << "  dimensions: " << card.dimensions_source << "\n\n";
  return text.str();
}

std::string robotCardLine(const RobotCard& card) {
  std::ostringstream text;
  text.imbue(std::locale::classic());
  text << card.name << "  " << vendorName(card.vendor) << " " << card.model << ", " << std::fixed
       << std::setprecision(0) << card.rated_payload_kg << " kg, RP " << std::setprecision(3)
       << card.rp_mm << " mm, stiffness " << stiffnessOrigin(card) << "\n";
  return text.str();
}

RobotList robotList(const std::vector<RobotCard>& cards) {
  RobotList out;
  Json list = Json::array();
  for (const RobotCard& card : cards) {
    list.push(robotCardJson(card));
    out.text += robotCardText(card);
    out.summary += robotCardLine(card);
  }
  out.json = Json::object();
  out.json.set("robots", list);
  return out;
}

}  // namespace roprec::api
