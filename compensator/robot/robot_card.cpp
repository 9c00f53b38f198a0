#include "compensator/robot/robot_card.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>

#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_node.hpp"

namespace fs = std::filesystem;

namespace roprec {

namespace {
std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}
bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && lower(s.substr(s.size() - suffix.size())) == suffix;
}
}  // namespace

Vendor vendorFromString(const std::string& s) {
  const std::string l = lower(s);
  if (l == "kuka") return Vendor::kKuka;
  if (l == "abb") return Vendor::kAbb;
  if (l == "fanuc") return Vendor::kFanuc;
  return Vendor::kGeneric;
}

std::string vendorName(Vendor v) {
  switch (v) {
    case Vendor::kKuka:
      return "KUKA";
    case Vendor::kAbb:
      return "ABB";
    case Vendor::kFanuc:
      return "FANUC";
    case Vendor::kGeneric:
      break;
  }
  return "generic";
}

bool JointCard::estimated() const { return source.rfind("estimate:", 0) == 0 || source.empty(); }

RobotCard loadRobotCard(const std::string& path) {
  const XmlNode root = loadXmlFile(path);
  if (root.name != "robot")
    root.fail("a robot card's root element is <robot>, got <" + root.name + ">");
  RobotCard card;
  card.file = path;
  card.name = root.str("name");
  card.vendor_label = root.str("vendor", "");
  card.vendor = vendorFromString(card.vendor_label);
  card.model = root.str("model", "");
  const std::string urdf = root.str("urdf");
  const fs::path dir = fs::path(path).parent_path();
  card.urdf_path =
      (fs::path(urdf).is_absolute() ? fs::path(urdf) : dir / urdf).lexically_normal().string();
  card.base_link = root.str("base_link", "");
  card.flange_link = root.str("flange_link", "");
  card.dimensions_source = root.str("dimensions_source", "");
  card.inertial_source = root.str("inertial_source", "");
  card.rated_payload_kg = root.number("rated_payload_kg", 0.0);

  const auto joints = root.childrenNamed("joint");
  if (joints.size() != 6) {
    root.fail("a robot card needs 6 <joint> elements, got " + std::to_string(joints.size()));
  }
  bool all_k = true;
  for (size_t i = 0; i < 6; ++i) {
    const XmlNode& j = *joints[i];
    JointCard& jc = card.joints[i];
    jc.name = j.str("name");
    jc.line = j.line;
    jc.source = j.str("source", "");
    if (j.has("stiffness")) {
      jc.stiffness = j.number("stiffness");
      if (!(jc.stiffness > 0)) j.fail("joint '" + jc.name + "': stiffness must be > 0 N m/rad");
    } else {
      all_k = false;
    }
    if (j.has("position_gain")) {
      jc.position_gain = j.number("position_gain");
      if (!(*jc.position_gain > 0))
        j.fail("joint '" + jc.name + "': position_gain must be > 0 1/s");
    }
    if (j.has("velocity_gain")) {
      jc.velocity_gain = j.number("velocity_gain");
      if (!(*jc.velocity_gain > 0)) j.fail("joint '" + jc.name + "': velocity_gain must be > 0");
    }
    jc.motor_inertia = j.number("motor_inertia", 0.0);
    if (jc.motor_inertia < 0) j.fail("joint '" + jc.name + "': motor_inertia must be >= 0");
    jc.controller_sign = j.number("controller_sign", 1.0);
    if (jc.controller_sign != 1.0 && jc.controller_sign != -1.0) {
      j.fail("joint '" + jc.name + "': controller_sign must be 1 or -1");
    }
    jc.controller_offset = j.number("controller_offset_deg", 0.0) * kDeg;
  }
  card.has_stiffness = all_k;
  if (const XmlNode* rp = root.child("repeatability")) {
    card.rp_mm = rp->number("rp_mm");
    if (!(card.rp_mm > 0)) rp->fail("rp_mm must be > 0");
    card.rp_source = rp->str("source", "");
  }
  if (const XmlNode* c = root.child("controller")) {
    card.gravity_compensated = c->boolean("gravity_compensated", false);
    card.calibration_load_kg = c->number("calibration_load_kg", 0.0);
    card.calibration_load_com = c->vec3("calibration_load_com_mm", Vec3::Zero()) * 1e-3;
    card.j23_coupling = c->number("j23_coupling", 0.0);
  }
  return card;
}

// The robots folder relative to the installed library's folder (set by CMake from the install
// dirs).
#ifndef ROPREC_ROBOTS_RELDIR
#define ROPREC_ROBOTS_RELDIR "../share/roprec/robots"
#endif

std::string bundledRobotsDir() {
  if (const char* env = std::getenv("ROPREC_ROBOTS_DIR"); env != nullptr && *env != '\0')
    return env;
  // An installed library: the robots folder next to it (<prefix>/lib/../share/roprec/robots),
  // found from the path of the loaded shared object that holds this function.
  static const std::string installed = [] {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&bundledRobotsDir), &info) == 0 ||
        info.dli_fname == nullptr || *info.dli_fname == '\0') {
      return std::string();
    }
    std::error_code ec;
    const fs::path dir =
        fs::absolute(fs::path(info.dli_fname), ec).parent_path() / ROPREC_ROBOTS_RELDIR;
    if (ec || !fs::is_directory(dir, ec)) return std::string();
    const fs::path real = fs::canonical(dir, ec);
    return (ec ? dir.lexically_normal() : real).string();
  }();
  if (!installed.empty()) return installed;
#ifdef ROPREC_ROBOTS_DIR
  return ROPREC_ROBOTS_DIR;  // the source tree's robots/ (build-tree use)
#else
  return "robots";
#endif
}

std::vector<std::string> bundledRobotNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(bundledRobotsDir(), ec)) {
    if (e.is_directory() && fs::exists(e.path() / "robot.xml"))
      names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

Robot loadRobot(const RobotRequest& request) {
  Robot robot;
  const std::string& r = request.robot;
  if (r.empty()) throw UsageError("no robot given (--robot NAME|robot.xml|file.urdf)");
  if (endsWith(r, ".urdf")) {
    robot.chain = loadUrdfChain(r, {request.base_link, request.tip_link});
    RobotCard& c = robot.card;
    c.name = robot.chain.robot_name;
    c.urdf_path = r;
    c.base_link = robot.chain.base_link;
    c.flange_link = robot.chain.tip_link;
    for (size_t i = 0; i < 6; ++i) c.joints[i].name = robot.chain.joints[i].name;
    return robot;
  }
  std::string card_path;
  if (endsWith(r, ".xml")) {
    card_path = r;
  } else {
    card_path = (fs::path(bundledRobotsDir()) / r / "robot.xml").string();
    if (!fs::exists(card_path)) {
      std::string known;
      for (const auto& n : bundledRobotNames()) known += (known.empty() ? "" : ", ") + n;
      throw InputError(
          "", 0,
          "unknown robot '" + r + "' (bundled: " + known + "; or give a robot.xml or .urdf path)");
    }
  }
  robot.card = loadRobotCard(card_path);
  UrdfChainRequest req{robot.card.base_link, robot.card.flange_link};
  if (!request.base_link.empty()) req.base_link = request.base_link;
  if (!request.tip_link.empty()) req.tip_link = request.tip_link;
  robot.chain = loadUrdfChain(robot.card.urdf_path, req);
  for (size_t i = 0; i < 6; ++i) {
    if (robot.card.joints[i].name != robot.chain.joints[i].name) {
      throw InputError(card_path, robot.card.joints[i].line,
                       "joint " + std::to_string(i + 1) + " is '" + robot.card.joints[i].name +
                           "' in the card but '" + robot.chain.joints[i].name +
                           "' in the URDF chain");
    }
  }
  robot.card.base_link = robot.chain.base_link;
  robot.card.flange_link = robot.chain.tip_link;
  return robot;
}

Eigen::Matrix<double, 6, 1> toControllerJoints(const RobotCard& card,
                                               const Eigen::Matrix<double, 6, 1>& q_urdf) {
  Eigen::Matrix<double, 6, 1> q;
  for (int i = 0; i < 6; ++i) {
    const JointCard& j = card.joints[static_cast<size_t>(i)];
    q[i] = j.controller_sign * q_urdf[i] + j.controller_offset;
  }
  q[2] += card.j23_coupling * q_urdf[1];
  return q;
}

Eigen::Matrix<double, 6, 1> fromControllerJoints(const RobotCard& card,
                                                 const Eigen::Matrix<double, 6, 1>& q_ctrl) {
  Eigen::Matrix<double, 6, 1> q;
  for (int i = 0; i < 6; ++i) {
    const JointCard& j = card.joints[static_cast<size_t>(i)];
    q[i] = (q_ctrl[i] - j.controller_offset) * j.controller_sign;
  }
  // q_ctrl3 = s3 q3 + o3 + c q2  =>  q3 = (q_ctrl3 - o3 - c q2) s3
  const JointCard& j3 = card.joints[2];
  q[2] = (q_ctrl[2] - j3.controller_offset - card.j23_coupling * q[1]) * j3.controller_sign;
  return q;
}

}  // namespace roprec
