#include "compensator/robot/urdf_loader.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "compensator/support/error.hpp"
#include "compensator/support/str_cat.hpp"
#include "compensator/support/xml_node.hpp"

namespace roprec {

std::string inertiaProblem(const Mat3& I) {
  if (!I.allFinite()) return "the inertia has a value that is not a finite number";
  const Eigen::SelfAdjointEigenSolver<Mat3> es(I);
  const Vec3& ev = es.eigenvalues();  // ascending
  const double tol = 1e-9 * std::max(1.0, ev.cwiseAbs().maxCoeff());
  if (ev.minCoeff() < -tol || ev[0] + ev[1] < ev[2] - tol) {
    return "principal moments must be >= 0 and satisfy the triangle inequality";
  }
  return "";
}

namespace {

/// Joint limits beyond ten turns either way are refused at load (a limit of -1e300
/// made the IK's turn enumeration loop 2^31 times).
constexpr double kMaxJointLimitRad = 10.0 * 2.0 * 3.14159265358979323846;

std::string readFile(const std::string& path) { return readInputFile(path, InputKind::kUrdf); }

/// Validation with line numbers before urdfdom sees the text.
struct UrdfIndex {
  std::map<std::string, int> link_line;
  std::map<std::string, int> joint_line;
  std::map<std::string, std::string> parent_joint_of_link;  // child link -> joint
  std::map<std::string, std::string> parent_of_link;        // child link -> parent link
  std::vector<std::string> link_order;
  int robot_line{1};
};

/// An <origin>: only xyz (m) and rpy (rad), each |value| <= 100 (a misspelt attribute would
/// silently be 0; 1e300 would overflow the kinematics). Throws InputError at its line.
void checkOrigin(const XmlNode& parent) {
  if (const XmlNode* o = parent.child("origin")) {
    allowOnly(*o, {"xyz", "rpy"});
    for (const char* k : {"xyz", "rpy"}) {
      if (o->has(k) && !(o->numbers(k, 3).cwiseAbs().maxCoeff() <= 100.0))
        o->fail(std::string("<origin> ") + k + " '" + o->str(k) + "' is beyond 100 " +
                (k[0] == 'x' ? "m" : "rad") + " (URDF lengths are in metres, angles in radians)");
    }
  }
}

/// A loop: a link that is its own ancestor. Each link is walked up once (a link already known to
/// reach the root ends the walk), so the check is linear in the links (times the map's log).
void checkNoLoop(const XmlNode& robot, const UrdfIndex& idx) {
  enum class State { kUnseen, kOnPath, kReachesRoot };
  std::map<std::string, State> state;
  for (const auto& [start, joint] : idx.parent_joint_of_link) {
    std::vector<std::string> path;
    std::string cur = start;
    while (true) {
      State& s = state[cur];
      if (s == State::kReachesRoot) break;
      if (s == State::kOnPath) {
        const std::string& j = idx.parent_joint_of_link.at(cur);
        throw InputError(robot.file, idx.joint_line.at(j),
                         "joint '" + j + "' is part of a kinematic loop (a URDF must be a tree)");
      }
      s = State::kOnPath;
      path.push_back(cur);
      const auto up = idx.parent_of_link.find(cur);
      if (up == idx.parent_of_link.end()) break;  // the root
      cur = up->second;
    }
    for (const std::string& l : path) state[l] = State::kReachesRoot;
  }
}

UrdfIndex validate(const XmlNode& robot) {
  UrdfIndex idx;
  idx.robot_line = robot.line;
  if (robot.name != "robot")
    robot.fail("root element is <" + robot.name + ">, a URDF needs <robot>");
  for (const XmlNode& e : robot.children) {
    if (e.name == "link") {
      const std::string name = e.str("name");
      if (idx.link_line.count(name)) e.fail("link '" + name + "' is defined twice");
      idx.link_line[name] = e.line;
      idx.link_order.push_back(name);
      // The URDF elements roprec reads or knows: a misspelt one (<inertail>, <axsi>) would
      // silently take urdfdom's default (no mass, the x axis).
      allowOnly(e, {"name"});
      allowChildren(e, {"inertial", "visual", "collision"});
      if (const XmlNode* in = e.child("inertial")) {
        allowChildren(*in, {"origin", "mass", "inertia"});
        checkOrigin(*in);
        const XmlNode* m = in->child("mass");
        if (m == nullptr) in->fail("<inertial> has no <mass>");
        allowOnly(*m, {"value"});
        const double mass = m->number("value");
        if (mass < 0) m->fail("negative mass " + m->str("value"));
        const XmlNode* I = in->child("inertia");
        if (I == nullptr) in->fail("<inertial> of link '" + name + "' has no <inertia>");
        allowOnly(*I, {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"});
        // read every number before building the matrix: a throw inside Eigen's comma
        // initializer aborts (its destructor asserts the count)
        const double ixx = I->number("ixx"), ixy = I->number("ixy"), ixz = I->number("ixz");
        const double iyy = I->number("iyy"), iyz = I->number("iyz"), izz = I->number("izz");
        Mat3 T;
        T << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
        if (const std::string why = inertiaProblem(T); !why.empty())
          I->fail(strCat("<inertia> of link '", name, "' is not physically valid: ", why));
      }
    }
  }
  for (const XmlNode& e : robot.children) {
    if (e.name != "joint") continue;
    const std::string name = e.str("name");
    const std::string type = e.str("type");
    if (idx.joint_line.count(name)) e.fail("joint '" + name + "' is defined twice");
    allowOnly(e, {"name", "type"});
    allowChildren(e, {"parent", "child", "origin", "axis", "limit", "dynamics", "safety_controller",
                      "calibration", "mimic"});
    idx.joint_line[name] = e.line;
    const XmlNode* p = e.child("parent");
    const XmlNode* c = e.child("child");
    if (p == nullptr) e.fail("joint '" + name + "' has no <parent>");
    if (c == nullptr) e.fail("joint '" + name + "' has no <child>");
    allowOnly(*p, {"link"});
    allowOnly(*c, {"link"});
    const std::string parent = p->str("link");
    const std::string child = c->str("link");
    if (!idx.link_line.count(parent))
      p->fail(strCat("joint '", name, "': unknown parent link '", parent, "'"));
    if (!idx.link_line.count(child))
      c->fail(strCat("joint '", name, "': unknown child link '", child, "'"));
    if (auto it = idx.parent_joint_of_link.find(child); it != idx.parent_joint_of_link.end()) {
      e.fail(strCat("joint '", name, "' closes a loop: link '", child,
                    "' already has the parent joint '", it->second, "' (a URDF must be a tree)"));
    }
    idx.parent_joint_of_link[child] = name;
    idx.parent_of_link[child] = parent;
    checkOrigin(e);
    if (const XmlNode* a = e.child("axis")) {
      allowOnly(*a, {"xyz"});
      const Eigen::Vector3d ax = a->numbers("xyz", 3);
      if (ax.norm() < 1e-12 && type != "fixed") a->fail("joint '" + name + "' has a zero axis");
      // a unit vector as written (URDF normalises it): a component beyond 10 is a corrupted
      // number, and normalising it would silently turn the axis
      if (!(ax.cwiseAbs().maxCoeff() <= 10.0)) {
        a->fail("joint '" + name + "' axis xyz '" + a->str("xyz") +
                "' is not a direction (components within -10 .. 10 expected, e.g. '0 0 1')");
      }
    }
    if (const XmlNode* l = e.child("limit")) {
      allowOnly(*l, {"lower", "upper", "velocity", "effort"});
      for (const char* k : {"lower", "upper", "velocity", "effort"}) {
        if (l->has(k)) (void)l->number(k);
      }
      // urdfdom requires effort and velocity on every <limit>
      for (const char* k : {"effort", "velocity"}) {
        if (!l->has(k))
          l->fail("joint '" + name + "': <limit> is missing the attribute '" + k + "'");
      }
    } else if (type == "revolute" || type == "prismatic") {
      e.fail(strCat("joint '", name, "' (", type, ") has no <limit>"));
    }
    if (type != "revolute" && type != "continuous" && type != "fixed" && type != "prismatic" &&
        type != "floating" && type != "planar") {
      e.fail(strCat("joint '", name, "' has an unknown type '", type, "'"));
    }
  }
  if (idx.link_line.empty()) robot.fail("the URDF has no <link>");
  std::vector<std::string> roots;
  for (const std::string& l : idx.link_order) {
    if (!idx.parent_joint_of_link.count(l)) roots.push_back(l);
  }
  if (roots.size() > 1) {
    throw InputError(robot.file, idx.link_line.at(roots[1]),
                     "link '" + roots[1] + "' has no parent joint, but '" + roots[0] +
                         "' is already the root: a URDF must be one connected tree");
  }
  checkNoLoop(robot, idx);
  return idx;
}

Pose toPose(const urdf::Pose& p) {
  Pose T = Pose::Identity();
  T.translation() = Vec3(p.position.x, p.position.y, p.position.z);
  double w = 0;
  double x = 0;
  double y = 0;
  double z = 0;
  p.rotation.getQuaternion(x, y, z, w);
  T.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  return T;
}

Inertial toInertial(const urdf::InertialSharedPtr& in) {
  Inertial out;
  if (!in) return out;
  out.present = true;
  out.mass = in->mass;
  const Pose T = toPose(in->origin);
  Mat3 I;
  I << in->ixx, in->ixy, in->ixz, in->ixy, in->iyy, in->iyz, in->ixz, in->iyz, in->izz;
  out.com = T.translation();
  out.inertia = T.linear() * I * T.linear().transpose();
  return out;
}

/// Inertial of `link` plus every link attached to it by fixed joints, in `link`'s frame.
Inertial bodyInertial(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& link) {
  Inertial total = toInertial(link->inertial);
  for (const auto& j : link->child_joints) {
    if (j->type != urdf::Joint::FIXED) continue;
    auto child = model.getLink(j->child_link_name);
    if (!child) continue;
    const Inertial sub = bodyInertial(model, child);
    total = combine(total, transformed(sub, toPose(j->parent_to_joint_origin_transform)));
  }
  return total;
}

bool isMoving(int type) {
  return type == urdf::Joint::REVOLUTE || type == urdf::Joint::CONTINUOUS ||
         type == urdf::Joint::PRISMATIC || type == urdf::Joint::FLOATING ||
         type == urdf::Joint::PLANAR;
}

}  // namespace

std::vector<std::string> urdfLinkNames(const std::string& path) {
  return validate(loadXmlFile(path, InputKind::kUrdf)).link_order;
}

ChainDescription loadUrdfChain(const std::string& path, const UrdfChainRequest& request) {
  const std::string text = readFile(path);
  const XmlNode robot = parseXmlText(text, path);
  const UrdfIndex idx = validate(robot);

  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(text);
  if (!model)
    throw InputError(path, idx.robot_line, "urdfdom rejected the URDF (see its structure)");

  const urdf::LinkConstSharedPtr root = model->getRoot();
  std::string base = request.base_link.empty() ? (root ? root->name : "") : request.base_link;
  std::string tip = request.tip_link;
  if (tip.empty()) {
    for (const char* cand : {"tool0", "flange"}) {
      if (idx.link_line.count(cand)) {
        tip = cand;
        break;
      }
    }
  }
  if (!idx.link_line.count(base)) {
    throw InputError(path, idx.robot_line, "unknown base link '" + base + "'");
  }
  if (tip.empty()) {
    // The deepest link of the subtree below the base, counted in moving joints (side branches
    // such as a balancing cylinder are shallower than the arm); ties: document order.
    std::string best = base;
    int best_depth = -1;
    std::vector<std::pair<urdf::LinkConstSharedPtr, int>> stack{{model->getLink(base), 0}};
    while (!stack.empty()) {
      auto [link, depth] = stack.back();
      stack.pop_back();
      if (depth > best_depth) {
        best_depth = depth;
        best = link->name;
      }
      for (auto it = link->child_joints.rbegin(); it != link->child_joints.rend(); ++it) {
        stack.emplace_back(model->getLink((*it)->child_link_name),
                           depth + (isMoving((*it)->type) ? 1 : 0));
      }
    }
    tip = best;
  }
  if (!idx.link_line.count(tip)) {
    throw InputError(path, idx.robot_line, "unknown tip link '" + tip + "'");
  }

  // The base may hang off the chain through fixed joints (e.g. FANUC's world frame `base` at J2
  // height is a fixed child of `base_link`): collect base -> root, fixed joints only.
  std::map<std::string, Pose> T_anc_base;  // ancestor link -> pose of the base in it
  {
    Pose T = Pose::Identity();
    urdf::LinkConstSharedPtr cur = model->getLink(base);
    T_anc_base[cur->name] = T;
    while (cur->parent_joint && cur->parent_joint->type == urdf::Joint::FIXED) {
      T = toPose(cur->parent_joint->parent_to_joint_origin_transform) * T;
      cur = model->getLink(cur->parent_joint->parent_link_name);
      T_anc_base[cur->name] = T;
    }
  }
  // Walk from the tip up to the base or to one of its fixed ancestors.
  std::vector<urdf::JointConstSharedPtr> path_joints;
  std::string meet = tip;
  for (urdf::LinkConstSharedPtr cur = model->getLink(tip); !T_anc_base.count(cur->name);) {
    const urdf::JointConstSharedPtr pj = cur->parent_joint;
    if (!pj) {
      throw InputError(path, idx.link_line.at(tip),
                       strCat("link '", tip, "' is not below the base link '", base, "'"));
    }
    path_joints.push_back(pj);
    cur = model->getLink(pj->parent_link_name);
    meet = cur->name;
  }
  std::reverse(path_joints.begin(), path_joints.end());

  ChainDescription chain;
  chain.file = path;
  chain.robot_name = model->getName();
  chain.base_link = base;
  chain.tip_link = tip;
  int n = 0;
  Pose pending = T_anc_base.at(meet).inverse();
  for (const auto& j : path_joints) {
    const int line = idx.joint_line.count(j->name) ? idx.joint_line.at(j->name) : idx.robot_line;
    const Pose O = toPose(j->parent_to_joint_origin_transform);
    if (j->type == urdf::Joint::FIXED) {
      pending = pending * O;
      continue;
    }
    if (j->type == urdf::Joint::PRISMATIC) {
      throw InputError(
          path, line,
          "joint '" + j->name + "' is prismatic: roprec models 6R chains (revolute joints only)");
    }
    if (j->type != urdf::Joint::REVOLUTE && j->type != urdf::Joint::CONTINUOUS) {
      throw InputError(path, line, "joint '" + j->name + "' is not revolute");
    }
    if (n >= 6) {
      throw InputError(
          path, line,
          strCat("the chain ", base, " -> ", tip, " has more than 6 revolute joints (at '", j->name,
                 "'): roprec needs a 6R chain"));
    }
    ChainJoint& cj = chain.joints[static_cast<size_t>(n)];
    cj.name = j->name;
    cj.child_link = j->child_link_name;
    cj.origin = pending * O;
    cj.axis = Vec3(j->axis.x, j->axis.y, j->axis.z).normalized();
    cj.continuous = j->type == urdf::Joint::CONTINUOUS;
    cj.line = line;
    if (j->limits && !cj.continuous) {
      cj.lower = j->limits->lower;
      cj.upper = j->limits->upper;
      cj.velocity = j->limits->velocity;
      cj.effort = j->limits->effort;
      // Range check (numbers are finite here: the reader refuses nan/inf): a revolute joint
      // turning more than ten turns either way is a unit or typing error (radians expected).
      for (const auto& [what, v] : {std::pair<const char*, double>{"lower", cj.lower},
                                    std::pair<const char*, double>{"upper", cj.upper}}) {
        if (!std::isfinite(v) || std::abs(v) > kMaxJointLimitRad) {
          throw InputError(
              path, line,
              "joint '" + j->name + "': <limit " + what + "=\"" + numberText(v) +
                  "\"> is out of range (|limit| <= " + numberText(kMaxJointLimitRad, 4) +
                  " rad = 10 turns; URDF limits are in radians)");
        }
      }
      if (!(cj.lower < cj.upper)) {
        throw InputError(path, line, "joint '" + j->name + "' has lower limit >= upper limit");
      }
    } else if (!cj.continuous) {
      throw InputError(path, line, "revolute joint '" + j->name + "' has no <limit>");
    } else {
      cj.lower = -2 * kPi;
      cj.upper = 2 * kPi;
    }
    pending = Pose::Identity();
    ++n;
  }
  if (n != 6) {
    throw InputError(path, idx.link_line.at(tip),
                     "the chain " + base + " -> " + tip + " has " + std::to_string(n) +
                         " revolute joints: roprec needs a 6R chain");
  }
  chain.tip = pending;

  // Body inertials: the child link of joint i plus every link rigidly attached to it through
  // fixed joints (moving side branches such as a balancing cylinder are not part of the body).
  bool all = true;
  for (int i = 0; i < 6; ++i) {
    const std::string& link = chain.joints[static_cast<size_t>(i)].child_link;
    const Inertial in = bodyInertial(*model, model->getLink(link));
    chain.inertials[static_cast<size_t>(i)] = in;
    if (!(in.mass > 0)) all = false;
  }
  chain.has_inertials = all;
  return chain;
}

}  // namespace roprec
