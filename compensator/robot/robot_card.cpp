#include "compensator/robot/robot_card.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <tuple>

#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"
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

std::string requireSource(const XmlNode& e) {
  std::string src = e.str("source", "");
  if (src.empty()) e.fail("<" + e.name + "> needs a source= for its numbers");
  return src;
}

int cardJointIndex(const RobotCard& card, const XmlNode& e, const std::string& name) {
  for (int i = 0; i < 6; ++i)
    if (card.joints[static_cast<size_t>(i)].name == name) return i;
  e.fail("<" + e.name + "> joint '" + name + "' is not one of the card's joints");
}

Counterbalance parseCounterbalance(const RobotCard& card, const XmlNode& e) {
  allowOnly(e, {"joint", "law", "action", "r_mm", "d_mm", "psi0_deg", "sign", "length_ref_mm",
                "preload_N", "rate_N_per_mm", "pressure_ref_MPa", "piston_area_mm2", "gas_volume_l",
                "polytropic_n", "sizing_fraction", "sizing_pose_deg", "source"});
  Counterbalance cb;
  cb.line = e.line;
  cb.joint = cardJointIndex(card, e, e.str("joint"));
  const std::string law = e.str("law");
  if (law != "spring" && law != "gas") e.fail("<counterbalance> law must be spring or gas");
  cb.law = law == "spring" ? Counterbalance::Law::kSpring : Counterbalance::Law::kGas;
  const std::string action = e.str("action");
  if (action != "push" && action != "pull") e.fail("<counterbalance> action must be push or pull");
  cb.action = action == "push" ? Counterbalance::Action::kPush : Counterbalance::Action::kPull;
  // plausible sizes (a corrupted number would silently move every gravity torque)
  for (const auto& [a, lo, hi] : std::initializer_list<std::tuple<const char*, double, double>>{
           {"r_mm", 0.0, 5000.0},
           {"d_mm", 0.0, 5000.0},
           {"length_ref_mm", 0.0, 10000.0},
           {"psi0_deg", -720.0, 720.0},
           {"preload_N", 0.0, 1e6},
           {"rate_N_per_mm", 0.0, 1e6},
           {"pressure_ref_MPa", 0.0, 100.0},
           {"piston_area_mm2", 0.0, 1e6},
           {"gas_volume_l", 0.0, 1000.0}}) {
    if (e.has(a) && !(std::fabs(e.number(a)) <= hi && e.number(a) >= lo)) {
      e.fail(std::string("<counterbalance> ") + a + " = " + numberText(e.number(a)) +
             " is outside the plausible range " + numberText(lo) + " .. " + numberText(hi));
    }
  }
  cb.r = e.number("r_mm") * 1e-3;
  cb.d = e.number("d_mm") * 1e-3;
  cb.psi0 = e.number("psi0_deg") * kDeg;
  cb.sign = e.number("sign", 1.0);
  cb.length_ref = e.number("length_ref_mm") * 1e-3;
  const auto need = [&](std::initializer_list<const char*> yes,
                        std::initializer_list<const char*> no) {
    for (const char* a : yes)
      if (!e.has(a)) e.fail("<counterbalance law=\"" + law + "\"> needs " + a);
    for (const char* a : no)
      if (e.has(a)) e.fail("<counterbalance law=\"" + law + "\"> has no " + a);
  };
  if (cb.law == Counterbalance::Law::kSpring) {
    need({"preload_N", "rate_N_per_mm"},
         {"pressure_ref_MPa", "piston_area_mm2", "gas_volume_l", "polytropic_n"});
    cb.force_ref = e.number("preload_N");
    cb.stiffness = e.number("rate_N_per_mm") * 1e3;
  } else {
    need({"pressure_ref_MPa", "piston_area_mm2", "gas_volume_l"}, {"preload_N", "rate_N_per_mm"});
    cb.pressure_ref = e.number("pressure_ref_MPa") * 1e6;
    cb.area = e.number("piston_area_mm2") * 1e-6;
    cb.volume_ref = e.number("gas_volume_l") * 1e-3;
    cb.polytropic = e.number("polytropic_n", 1.0);
  }
  cb.source = requireSource(e);
  return cb;
}

void parseWeightElements(const XmlNode& root, RobotCard& card) {
  if (const XmlNode* e = root.child("counterbalance")) {
    if (root.childrenNamed("counterbalance").size() > 1)
      e->fail("a robot card has at most one <counterbalance>");
    card.counterbalance = parseCounterbalance(card, *e);
    if (e->has("sizing_fraction")) {
      card.balancer_sizing_fraction = e->number("sizing_fraction");
      if (!(card.balancer_sizing_fraction > 0 && card.balancer_sizing_fraction <= 1.5))
        e->fail("sizing_fraction must lie in (0, 1.5]");
      if (!e->has("sizing_pose_deg")) e->fail("sizing_fraction needs sizing_pose_deg");
      card.balancer_sizing_pose =
          fromControllerJoints(card, e->numbers("sizing_pose_deg", 6) * kDeg);
    }
  }
  if (const XmlNode* g = root.child("gravity")) {
    allowOnly(*g, {"model", "source"});
    const std::string model = g->str("model");
    if (model != "none" && model != "links")
      g->fail("<gravity> model must be \"links\" (the default) or \"none\"");
    card.gravity_modelled = model == "links";
    card.gravity_source = g->str("source", "");
  }
  for (const XmlNode* l : root.childrenNamed("link")) {
    allowOnly(*l, {"name", "mass_kg", "com_mm", "inertia_kgm2", "source"});
    RobotCard::LinkInertial li;
    li.name = l->str("name");
    li.line = l->line;
    li.mass = l->number("mass_kg");
    if (!(li.mass > 0)) l->fail("<link> mass_kg must be > 0, got " + l->str("mass_kg"));
    if (!l->has("com_mm")) l->fail("<link> needs com_mm=\"x y z\" (link frame)");
    li.com = l->vec3("com_mm", Vec3::Zero()) * 1e-3;
    if (l->has("inertia_kgm2")) {
      const Eigen::VectorXd v = l->numbers("inertia_kgm2", 6);  // ixx ixy ixz iyy iyz izz
      Mat3 I;
      I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
      if (const std::string why = inertiaProblem(I); !why.empty())
        l->fail("<link name=\"" + li.name + "\"> inertia_kgm2: " + why);
      li.inertia = I;
    }
    li.source = requireSource(*l);
    card.links.push_back(li);
  }
}
}  // namespace

Eigen::Matrix<double, 6, 1> vendorCalibrationPoseDeg(Vendor v) {
  Eigen::Matrix<double, 6, 1> q = Eigen::Matrix<double, 6, 1>::Zero();
  if (v == Vendor::kKuka) {
    q[1] = -90.0;
    q[2] = 90.0;
  }
  return q;
}

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
  const XmlNode root = loadXmlFile(path, InputKind::kRobotCard);
  if (root.name != "robot")
    root.fail("a robot card's root element is <robot>, got <" + root.name + ">");
  allowOnly(root, {"name", "vendor", "model", "urdf", "base_link", "flange_link",
                   "rated_payload_kg", "dimensions_source", "inertial_source"});
  allowChildren(root, {"joint", "repeatability", "controller", "counterbalance", "gravity", "link",
                       "calibration", "accuracy"});
  allowAtMostOnce(root, {"repeatability", "controller", "counterbalance", "gravity", "calibration",
                         "accuracy"});
  RobotCard card;
  card.file = path;
  card.name = root.str("name");
  card.vendor_label = root.str("vendor", "");
  card.vendor = vendorFromString(card.vendor_label);
  card.model = root.str("model", "");
  const std::string urdf = root.str("urdf");
  card.urdf_line = root.line;
  const fs::path dir = fs::path(path).parent_path();
  card.urdf_path =
      (fs::path(urdf).is_absolute() ? fs::path(urdf) : dir / urdf).lexically_normal().string();
  card.base_link = root.str("base_link", "");
  card.flange_link = root.str("flange_link", "");
  card.dimensions_source = root.str("dimensions_source", "");
  card.inertial_source = root.str("inertial_source", "");
  card.rated_payload_kg = root.number("rated_payload_kg", 0.0);
  if (card.rated_payload_kg < 0)
    root.fail("rated_payload_kg must be >= 0, got " + root.str("rated_payload_kg"));

  const auto joints = root.childrenNamed("joint");
  if (joints.size() != 6) {
    root.fail("a robot card needs 6 <joint> elements, got " + std::to_string(joints.size()));
  }
  bool all_k = true;
  for (size_t i = 0; i < 6; ++i) {
    const XmlNode& j = *joints[i];
    JointCard& jc = card.joints[i];
    allowOnly(j, {"name", "stiffness", "position_gain", "velocity_gain", "motor_inertia",
                  "controller_sign", "controller_offset_deg", "source"});
    jc.name = j.str("name");
    jc.line = j.line;
    jc.source = j.str("source", "");
    if (j.has("stiffness")) {
      jc.stiffness = j.number("stiffness");
      // 1e12 N m/rad is rigid for any robot (identified joints: 1e4-1e8), below 100 N m/rad a
      // joint could not hold its own link: beyond either is a typo or a unit error.
      if (!(jc.stiffness >= 100 && jc.stiffness <= 1e12))
        j.fail("joint '" + jc.name + "': stiffness must be in [100, 1e12] N m/rad, got " +
               j.str("stiffness"));
    } else {
      all_k = false;
    }
    if (j.has("position_gain")) {
      jc.position_gain = j.number("position_gain");
      if (!(*jc.position_gain > 0 && *jc.position_gain <= 1e4))
        j.fail("joint '" + jc.name + "': position_gain must be in (0, 1e4] 1/s, got " +
               j.str("position_gain"));
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
  const XmlNode* rp = root.child("repeatability");
  if (rp == nullptr) {
    root.fail(
        "the robot card has no <repeatability rp_mm=\"...\" source=\"...\"/> (ISO 9283 pose "
        "repeatability RP, from the datasheet): without it the repeatability term of U_robot "
        "would silently be 0");
  }
  allowOnly(*rp, {"rp_mm", "standard", "source"});
  card.rp_mm = rp->number("rp_mm");
  if (!(card.rp_mm > 0)) rp->fail("rp_mm must be > 0, got " + rp->str("rp_mm"));
  card.rp_source = rp->str("source", "");
  if (const XmlNode* ac = root.child("accuracy")) {
    allowOnly(*ac, {"ap_mm", "standard", "source"});
    card.accuracy_ap_mm = ac->number("ap_mm");
    if (!(card.accuracy_ap_mm > 0 && card.accuracy_ap_mm <= 20))
      ac->fail("ap_mm (absolute pose accuracy) must lie in (0, 20] mm, got " + ac->str("ap_mm"));
    card.accuracy_source = requireSource(*ac);
    card.accuracy_line = ac->line;
  }
  Eigen::Matrix<double, 6, 1> cal_deg = vendorCalibrationPoseDeg(card.vendor);
  card.calibration_pose_source =
      "vendor default (" + vendorName(card.vendor) + "; docs/model.md section 6.3)";
  if (const XmlNode* c = root.child("controller")) {
    allowOnly(*c, {"gravity_compensated", "j23_coupling", "calibration_load_kg",
                   "calibration_load_com_mm", "calibration_pose_deg", "calibration_pose_source",
                   "source"});
    card.controller_line = c->line;
    card.gravity_compensated = c->boolean("gravity_compensated", false);
    card.calibration_load_kg = c->number("calibration_load_kg", 0.0);
    if (card.calibration_load_kg < 0)
      c->fail("calibration_load_kg must be >= 0, got " + c->str("calibration_load_kg"));
    card.calibration_load_com = c->vec3("calibration_load_com_mm", Vec3::Zero()) * 1e-3;
    card.j23_coupling = c->number("j23_coupling", 0.0);
    if (card.j23_coupling != 0.0 && card.j23_coupling != 1.0 && card.j23_coupling != -1.0) {
      c->fail(
          "j23_coupling must be -1, 0 or 1 (a parallel linkage couples J3 to J2 one to one; "
          "FANUC: -controller_sign of J2, every other vendor 0), got " +
          c->str("j23_coupling"));
    }
    if (c->has("calibration_pose_deg")) {
      cal_deg = c->numbers("calibration_pose_deg", 6);
      card.calibration_pose_source = c->str("calibration_pose_source", "");
      if (card.calibration_pose_source.empty())
        c->fail("calibration_pose_deg needs calibration_pose_source");
    } else if (c->has("calibration_pose_source")) {
      card.calibration_pose_source = c->str("calibration_pose_source");
    }
  }
  card.calibration_pose = fromControllerJoints(card, cal_deg * kDeg);
  parseWeightElements(root, card);
  if (const XmlNode* cal = root.child("calibration")) {
    std::array<std::string, 6> names;
    for (size_t i = 0; i < 6; ++i) names[i] = card.joints[i].name;
    card.calibration = parseCalibration(*cal, names);
  }
  return card;
}

// The robots folder relative to the installed library's folder (set by CMake from the install
// dirs).
#ifndef ROPREC_ROBOTS_RELDIR
#define ROPREC_ROBOTS_RELDIR "../share/roprec/robots"
#endif

namespace {

// The folder of the loaded shared object that holds this code (libroprec), or "".
fs::path loadedLibraryDir() {
  const std::string module = platform::loadedModulePath();
  if (module.empty()) return {};
  std::error_code ec;
  const fs::path dir = fs::absolute(platform::fromUtf8(module), ec).parent_path();
  return ec ? fs::path() : dir;
}

// True when `dir` lies in the build tree (libroprec in build/lib, or a binary that links the
// objects, e.g. a fuzz harness): the only place the source tree's robots/ is used from.
bool inBuildTree([[maybe_unused]] const fs::path& dir) {
#ifdef ROPREC_BUILD_DIR
  std::error_code ec;
  const fs::path build = fs::weakly_canonical(fs::path(ROPREC_BUILD_DIR), ec);
  const fs::path here = fs::weakly_canonical(dir, ec);
  if (ec || dir.empty()) return false;
  const auto [b, h] = std::mismatch(build.begin(), build.end(), here.begin(), here.end());
  return b == build.end();
#else
  return false;
#endif
}

}  // namespace

std::string bundledRobotsDir() {
  if (const char* env = std::getenv("ROPREC_ROBOTS_DIR"); env != nullptr && *env != '\0')
    return env;
  // An installed library: the robots folder next to it (<prefix>/lib/../share/roprec/robots),
  // found from the path of the loaded shared object that holds this function. The build tree's
  // library uses the source tree's robots/; an installed one never does.
  static const fs::path lib_dir = loadedLibraryDir();
  const fs::path dir = lib_dir / platform::fromUtf8(ROPREC_ROBOTS_RELDIR);
  std::error_code ec;
  if (!lib_dir.empty() && fs::is_directory(dir, ec)) {
    const fs::path real = fs::canonical(dir, ec);
    return platform::toUtf8(ec ? dir.lexically_normal() : real);
  }
#ifdef ROPREC_ROBOTS_DIR
  if (inBuildTree(lib_dir)) return ROPREC_ROBOTS_DIR;  // the source tree's robots/
#endif
  throw InputError("", 0,
                   "no bundled robots: " + platform::toUtf8(dir.lexically_normal()) +
                       " does not exist (reinstall roprec, or set the environment variable "
                       "ROPREC_ROBOTS_DIR to a folder of robot cards, e.g. the robots/ folder of "
                       "roprec's source)");
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

namespace {
/// Card weight data into the chain: <link> overrides, the balancer, the gravity model; checks the
/// balancer and the calibration pose against the joint ranges.
void applyWeightCard(Robot& robot) {
  RobotCard& card = robot.card;
  ChainDescription& chain = robot.chain;
  for (const RobotCard::LinkInertial& li : card.links) {
    int body = -1;
    for (int i = 0; i < 6; ++i)
      if (chain.joints[static_cast<size_t>(i)].child_link == li.name) body = i;
    if (body < 0) {
      std::string names;
      for (const ChainJoint& j : chain.joints) names += (names.empty() ? "" : ", ") + j.child_link;
      throw InputError(card.file, li.line,
                       "<link name=\"" + li.name +
                           "\"> is not a moving body of the chain (child links: " + names + ")");
    }
    Inertial& in = chain.inertials[static_cast<size_t>(body)];
    in.mass = li.mass;
    in.com = li.com;
    if (li.inertia) in.inertia = *li.inertia;
    in.present = true;
  }
  bool all = true;
  for (const Inertial& in : chain.inertials) all = all && in.mass > 0;
  chain.has_inertials = all;
  if (card.counterbalance.present()) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(card.counterbalance.joint)];
    const std::string why = balancerProblem(card.counterbalance, j.lower, j.upper);
    if (!why.empty())
      throw InputError(card.file, card.counterbalance.line, "<counterbalance>: " + why);
  }
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(i)];
    const double q = card.calibration_pose[i];
    if (q < j.lower - 1e-9 || q > j.upper + 1e-9) {
      throw InputError(card.file, card.controller_line,
                       "the calibration pose puts joint '" + j.name + "' outside its limits");
    }
  }
  chain.counterbalance = card.counterbalance;
  chain.gravity_modelled = card.gravity_modelled;
}
}  // namespace

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
    robot.real_chain = robot.chain;
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
  try {
    robot.chain = loadUrdfChain(robot.card.urdf_path, req);
  } catch (const InputError& e) {
    if (e.line() > 0 || e.file() != robot.card.urdf_path) throw;
    // an error about the URDF as a whole (cannot open it, no chain): point at the card's line
    // that names it
    throw InputError(card_path, robot.card.urdf_line, e.message() + " (URDF " + e.file() + ")");
  }
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
  applyWeightCard(robot);
  robot.real_chain =
      robot.card.calibration ? calibratedChain(robot.chain, *robot.card.calibration) : robot.chain;
  return robot;
}

namespace {
/// Line of `<link name="...">` in the URDF (the robot line if not found).
int urdfLinkLine(const std::string& urdf, const std::string& link) {
  const XmlNode root = loadXmlFile(urdf, InputKind::kUrdf);
  for (const XmlNode* l : root.childrenNamed("link"))
    if (l->str("name", "") == link) return l->line;
  return root.line;
}
}  // namespace

void requireGravityModel(const Robot& robot) {
  if (!robot.card.gravity_modelled) return;
  for (int i = 0; i < 6; ++i) {
    if (robot.chain.inertials[static_cast<size_t>(i)].mass > 0) continue;
    const std::string& link = robot.chain.joints[static_cast<size_t>(i)].child_link;
    const std::string where = robot.card.file.empty() ? "a robot card" : robot.card.file;
    std::string msg = "link '" + link + "' (moved by joint '";
    msg += robot.chain.joints[static_cast<size_t>(i)].name;
    msg += "') has no <inertial> mass, so its weight cannot be modelled; hint: give <link name=\"";
    msg += link;
    msg += "\" mass_kg=\"...\" com_mm=\"x y z\" source=\"...\"/> in ";
    msg += where;
    msg += ", or declare <gravity model=\"none\" source=\"...\"/> there";
    throw InputError(robot.chain.file, urdfLinkLine(robot.chain.file, link), msg);
  }
}

std::string gravityNotModelledNote(const RobotCard& card) {
  if (card.gravity_modelled) return "";
  return "gravity is not modelled (robot card <gravity model=\"none\"/>" +
         (card.gravity_source.empty() ? std::string() : ": " + card.gravity_source) +
         "): link and tool weight, the balancer and the controller's gravity reference are "
         "ignored; only process loads deflect the robot";
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
