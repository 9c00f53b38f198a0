#include "compensator/precision/card_scaffold.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <regex>

#include "compensator/precision/card_writer.hpp"
#include "compensator/robot/card_check.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_escape.hpp"
#include "compensator/support/xml_node.hpp"

namespace fs = std::filesystem;

namespace roprec {

namespace {

/// Uncalibrated absolute accuracy (ISO 9283 AP) class prior, mm (estimate, docs/cards.md §6).
constexpr double kClassAccuracyMm = 1.0;

constexpr double kAligned = 1.0 - 1e-6;
/// Share of the total robot mass of moving bodies 1..6 (the base takes the remaining 22 %).
constexpr std::array<double, 6> kMassFraction = {0.30, 0.18, 0.22, 0.05, 0.025, 0.005};

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::optional<Vendor> vendorFromName(const std::string& robot_name) {
  const std::string n = lowerCase(robot_name);
  if (n.find("kuka") != std::string::npos || std::regex_search(n, std::regex("(^|_)kr_?\\d")))
    return Vendor::kKuka;
  if (n.find("abb") != std::string::npos || n.find("irb") != std::string::npos) return Vendor::kAbb;
  if (n.find("fanuc") != std::string::npos) return Vendor::kFanuc;
  return std::nullopt;
}

std::optional<double> payloadFromName(const std::string& robot_name, Vendor v) {
  const std::string n = lowerCase(robot_name);
  std::smatch m;
  const auto find = [&](const char* re) { return std::regex_search(n, m, std::regex(re)); };
  bool hit = false;
  if (v == Vendor::kKuka) hit = find("kr_?(\\d+)");
  if (v == Vendor::kAbb) hit = find("irb_?\\d+_(\\d+)_\\d+");
  if (v == Vendor::kFanuc) hit = find("i[abcd](\\d+)f?($|_)") || find("(?:^|_)m(\\d+)i");
  if (!hit) return std::nullopt;
  const double p = std::stod(m[1].str());
  return p > 0 ? std::optional<double>(p) : std::nullopt;
}

bool hasLink(const std::string& urdf, const std::string& name) {
  const std::vector<std::string> names = urdfLinkNames(urdf);
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string findFlange(const std::string& urdf, const std::string& root) {
  std::string tried;
  for (const char* cand : {"tool0", "flange"}) {
    if (!hasLink(urdf, cand)) continue;
    const ChainDescription c = loadUrdfChain(urdf, {root, cand});
    const double cz = flangeZOutCosine(c);
    if (cz > kAligned) return cand;
    tried += std::string(tried.empty() ? "" : ", ") + cand + " (z.out " + cFixed(cz, 3) + ")";
  }
  throw InputError(
      urdf, 0,
      "no link with z out of the flange" +
          (tried.empty() ? std::string(" (no tool0 or flange link)") : " (tried " + tried + ")") +
          "; hint: add a fixed link tool0 on the last link with z along the joint-6 "
          "axis pointing away from the wrist (ROS-Industrial: rpy=\"0 1.5708 0\" on "
          "an x-out flange)");
}

/// FANUC World: `base` on the J1 axis at J2 height, else the root.
std::string findBase(const std::string& urdf, const std::string& root, const std::string& tip,
                     Vendor v) {
  if (v != Vendor::kFanuc || !hasLink(urdf, "base")) return root;
  const ChainDescription c = loadUrdfChain(urdf, {"base", tip});
  const ChainZeroGeometry g = zeroGeometry(c);
  return std::abs(g.p[1].z()) < 1e-6 ? "base" : root;
}

struct JointSigns {
  std::array<double, 6> sign{};
  double j23{0.0};
};

JointSigns jointSigns(const ChainDescription& chain, const VendorConvention& conv) {
  const ChainZeroGeometry g = zeroGeometry(chain);
  JointSigns s;
  for (size_t i = 0; i < 6; ++i) {
    const double d = g.a[i].dot(conv.axes[i]);
    if (std::abs(d) < kAligned) {
      throw InputError(chain.file, chain.joints[i].line,
                       "joint '" + chain.joints[i].name + "' is not along the vendor's axis " +
                           std::to_string(i + 1) +
                           " at the URDF zero pose (docs/cards.md lists the conventions); "
                           "hint: check --vendor, or give the card's joint conventions by hand");
    }
    s.sign[i] = d > 0 ? 1.0 : -1.0;
  }
  if (const std::string arm = lowerArmProblem(chain, Eigen::Matrix<double, 6, 1>::Zero(), conv);
      !arm.empty()) {
    throw InputError(chain.file, chain.joints[1].line,
                     arm + "; hint: check --vendor, or give the card's joint offsets by hand");
  }
  s.j23 = conv.j23_coupled ? -s.sign[1] : 0.0;
  return s;
}

/// A solid cylinder along `seg` (link frame), inertia about its centre in the link frame.
Mat3 cylinderInertia(double m, const Vec3& seg, const Vec3& fallback_axis) {
  const double L = std::max(seg.norm(), 0.2);
  const double r = 0.25 * L;
  const Vec3 d = seg.norm() > 1e-6 ? Vec3(seg.normalized()) : Vec3(fallback_axis.normalized());
  const double ia = 0.5 * m * r * r;
  const double ip = m * (3 * r * r + L * L) / 12.0;
  return ip * (Mat3::Identity() - d * d.transpose()) + ia * d * d.transpose();
}

std::string num(double v) { return cGeneral(std::abs(v) < 1e-12 ? 0.0 : v, 5); }
std::string vec(const Vec3& v, double scale) {
  return num(v.x() * scale) + " " + num(v.y() * scale) + " " + num(v.z() * scale);
}
std::string attr(const std::string& s) { return escapeXml(s, '"'); }

struct Ctx {
  const CardScaffoldRequest& req;
  ChainDescription chain;
  CardScaffold out;
  JointSigns signs;
  std::string model;
  double mass{0.0};
  std::string mass_rule;
  bool payload_guessed{false};
};

std::string stiffnessSource(const Ctx& c, int i) {
  const StiffnessClass cls = stiffnessClass(c.out.payload_kg);
  std::string s = "estimate: class value, no identified set of this robot given; " + cls.rule +
                  " (Jiao J. et al., Chinese J. Mech. Eng. 35:115 (2022), "
                  "doi:10.1186/s10033-022-00778-1: KUKA KR500 k" +
                  std::to_string(i + 1) + " = " + formatCardNumber(stiffnessClass(0).k[i]) +
                  " N m/rad)";
  if (cls.factor != 1.0)
    s += ", factor " + cGeneral(cls.factor, 4) + " for " + num(c.out.payload_kg) + " kg";
  return s +
         "; expect 2-3x on k4-k6; identify with roprec verify --calibrate. Position gain: "
         "estimate: typical position-loop gain Kv of industrial robots (30-60 1/s), not "
         "published";
}

void writeJoints(const Ctx& c, std::string& x) {
  const StiffnessClass cls = stiffnessClass(c.out.payload_kg);
  for (size_t i = 0; i < 6; ++i) {
    x += "  <joint name=\"" + attr(c.chain.joints[i].name) + "\" stiffness=\"" +
         formatCardNumber(cls.k[static_cast<int>(i)]) + "\" position_gain=\"" +
         num(kClassPositionGain) + "\"";
    if (c.signs.sign[i] < 0) x += " controller_sign=\"-1\"";
    x += "\n         source=\"" + attr(stiffnessSource(c, static_cast<int>(i))) + "\"/>\n";
  }
}

/// <link> estimates for the bodies whose URDF inertial is missing or a placeholder.
std::string writeLinks(Ctx& c) {
  const std::array<bool, 6> ph = placeholderInertials(c.chain);
  std::string x;
  int n = 0;
  for (size_t i = 0; i < 6; ++i) {
    if (c.chain.inertials[i].mass > 0 && !ph[i]) continue;
    ++n;
    const Vec3 seg = i < 5 ? c.chain.joints[i + 1].origin.translation() : c.chain.tip.translation();
    const double m = kMassFraction[i] * c.mass;
    const Mat3 I = cylinderInertia(m, seg, c.chain.joints[i].axis);
    const std::string why = ph[i] ? "the URDF's inertial is a placeholder" : "the URDF has none";
    x += "  <link name=\"" + attr(c.chain.joints[i].child_link) + "\" mass_kg=\"" + num(m) +
         "\" com_mm=\"" + vec(seg * 0.5, 1e3) + "\"\n        inertia_kgm2=\"" + num(I(0, 0)) + " " +
         num(I(0, 1)) + " " + num(I(0, 2)) + " " + num(I(1, 1)) + " " + num(I(1, 2)) + " " +
         num(I(2, 2)) + "\"\n        source=\"" +
         attr("estimate: " + why + "; " + cGeneral(kMassFraction[i] * 100, 3) + " % of the " +
              c.mass_rule +
              ", a solid cylinder along the link segment (length max(segment, 0.2 "
              "m), radius a quarter of it), centre of mass at its middle") +
         "\"/>\n";
  }
  if (n > 0) {
    c.out.confirm.push_back(std::to_string(n) + " link inertial(s) are class estimates from the " +
                            c.mass_rule +
                            ": give the vendor's link masses and centres of mass if you have them "
                            "(the J2/J3 gravity sag depends on them)");
  }
  return x;
}

std::string inertialSource(const Ctx& c, bool any_estimate) {
  if (!any_estimate)
    return "URDF <inertial> elements (" + fs::path(c.req.urdf).filename().string() +
           "): confirm they are the vendor's data";
  return "estimate: see each <link> (" + c.mass_rule + ")";
}

std::string writeCard(Ctx& c) {
  const fs::path card_dir = fs::absolute(fs::path(c.req.card_path)).parent_path();
  const std::string urdf_rel =
      fs::relative(fs::weakly_canonical(fs::absolute(c.req.urdf)), fs::weakly_canonical(card_dir))
          .generic_string();
  const std::string links = writeLinks(c);
  const std::string vendor = vendorName(c.out.vendor);
  std::string x = "<?xml version=\"1.0\"?>\n";
  x += "<!-- Robot card written by roprec card new (schema: robots/README.md, docs/cards.md). "
       "Every number carries its\n     source; \"estimate:\" marks estimated values: confirm or "
       "replace them, then run roprec card check. -->\n";
  x += "<robot name=\"" + attr(c.chain.robot_name) + "\" vendor=\"" + vendor + "\" model=\"" +
       attr(c.model) + "\"\n       urdf=\"" + attr(urdf_rel) + "\" base_link=\"" +
       attr(c.out.base_link) + "\" flange_link=\"" + attr(c.out.flange_link) +
       "\"\n       rated_payload_kg=\"" + num(c.out.payload_kg) +
       "\"\n       dimensions_source=\"" +
       attr("URDF " + fs::path(c.req.urdf).filename().string() + " (robot '" + c.chain.robot_name +
            "'): link lengths and joint ranges as given there; confirm against the " + vendor +
            " data sheet") +
       "\"\n       inertial_source=\"" + attr(inertialSource(c, !links.empty())) + "\">\n";
  writeJoints(c, x);
  x += "  <repeatability rp_mm=\"" + num(kClassRepeatabilityMm) +
       "\" standard=\"ISO 9283\"\n                 source=\"" +
       attr(
           "estimate: class value, the upper end of the ISO 9283 pose repeatability of "
           "industrial 6R arms (bundled 120-185 kg arms: 0.05-0.07 mm); replace it by the data "
           "sheet's RP") +
       "\"/>\n";
  x += "  <accuracy ap_mm=\"" + num(kClassAccuracyMm) +
       "\" standard=\"ISO 9283\"\n            source=\"" +
       attr(
           "estimate: class value; uncalibrated six-axis arms are 0.5-2 mm off (Slamani, "
           "Nubiola, Bonev, Industrial Robot 39(1), 2012); replace it by a measured AP, or "
           "calibrate the robot (<calibration>, docs/cards.md section 5)") +
       "\"/>\n";
  x += "  <controller gravity_compensated=\"false\" j23_coupling=\"" + num(c.signs.j23) +
       "\"\n              calibration_pose_source=\"" +
       attr("vendor default (" + vendor + " " + vendorConvention(c.out.vendor)->home_text +
            ", controller convention); confirm the robot was mastered there without a tool") +
       "\"/>\n";
  x += links;
  x += "</robot>\n";
  return x;
}

void listConfirm(Ctx& c) {
  auto& k = c.out.confirm;
  const std::string vendor = vendorName(c.out.vendor);
  if (!c.req.vendor)
    k.insert(k.begin(), "vendor " + vendor + " was read from the URDF robot name '" +
                            c.chain.robot_name + "'");
  if (c.payload_guessed)
    k.push_back("rated_payload_kg " + num(c.out.payload_kg) +
                " was read from the URDF robot name: confirm it with the data sheet");
  k.push_back("link lengths and joint ranges of the URDF against the " + vendor + " data sheet");
  k.push_back("joint stiffness: class estimate (" + stiffnessClass(c.out.payload_kg).rule +
              "); identify the robot with roprec verify --calibrate");
  k.push_back("repeatability rp_mm " + num(kClassRepeatabilityMm) +
              " mm is a class estimate: enter the data sheet's ISO 9283 RP");
  k.push_back("absolute accuracy ap_mm " + num(kClassAccuracyMm) +
              " mm is a class estimate: measure the robot's AP or calibrate it");
  k.push_back("position_gain " + num(kClassPositionGain) +
              " 1/s is a typical value, not the robot's");
  k.push_back(
      "no axis-2 balancer is modelled: if the arm has one, add <counterbalance> "
      "(robots/README.md)");
  k.push_back(
      "gravity_compensated=\"false\": set it to \"true\" if the controller has the "
      "absolute-accuracy option (or say so in the cell's <controller>)");
  if (c.out.vendor == Vendor::kFanuc && c.out.base_link != "base")
    k.push_back("the URDF has no World frame at J2 height: poses are in '" + c.out.base_link +
                "', not in FANUC World");
}

}  // namespace

double classRobotMassKg(double payload_kg) { return 34.0 * std::pow(payload_kg, 0.7); }

CardScaffold scaffoldCard(const CardScaffoldRequest& req) {
  const ChainDescription root_chain = loadUrdfChain(req.urdf, {});
  const std::string root = root_chain.base_link;
  Ctx c{req, {}, {}, {}, req.model.empty() ? root_chain.robot_name : req.model, 0.0, {}, false};
  if (req.vendor) {
    c.out.vendor = *req.vendor;
  } else if (const auto v = vendorFromName(root_chain.robot_name)) {
    c.out.vendor = *v;
  } else {
    throw UsageError("cannot tell the vendor from the URDF robot name '" + root_chain.robot_name +
                     "': give --vendor KUKA|ABB|FANUC");
  }
  if (c.out.vendor == Vendor::kGeneric) throw UsageError("--vendor must be KUKA, ABB or FANUC");
  if (req.payload_kg) {
    c.out.payload_kg = *req.payload_kg;
  } else if (const auto p = payloadFromName(root_chain.robot_name, c.out.vendor)) {
    c.out.payload_kg = *p;
    c.payload_guessed = true;
  } else {
    throw UsageError("cannot read the rated payload from the URDF robot name '" +
                     root_chain.robot_name + "': give --payload-kg (data sheet)");
  }
  if (!(c.out.payload_kg > 0 && c.out.payload_kg <= 2500))
    throw UsageError("--payload-kg must lie in (0, 2500] kg");
  c.out.flange_link = findFlange(req.urdf, root);
  c.out.base_link = findBase(req.urdf, root, c.out.flange_link, c.out.vendor);
  c.chain = loadUrdfChain(req.urdf, {c.out.base_link, c.out.flange_link});
  c.signs = jointSigns(c.chain, *vendorConvention(c.out.vendor));
  if (req.mass_kg) {
    c.mass = *req.mass_kg;
    c.mass_rule = "robot mass " + num(c.mass) + " kg (given)";
  } else {
    c.mass = classRobotMassKg(c.out.payload_kg);
    c.mass_rule = "class robot mass 34 kg x (payload/kg)^0.7 = " + cGeneral(c.mass, 4) +
                  " kg (fit to data-sheet masses of 16-185 kg arms; give --mass-kg from the data "
                  "sheet)";
  }
  listConfirm(c);
  c.out.xml = writeCard(c);
  return c.out;
}

}  // namespace roprec
