#include "compensator/robot/urdf_writer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "compensator/support/error.hpp"
#include "compensator/support/xml_node.hpp"

namespace roprec {

namespace {

/// The chain in the URDF tree: the joints from A, the nearest common ancestor of base_link and
/// tip_link, down to tip_link (chain order), and base_link's pose in A (a FANUC World frame `base`
/// hangs off base_link beside joint 1: A = base_link there).
struct UrdfPath {
  std::vector<const XmlNode*> down;
  std::vector<const XmlNode*> to_base;  ///< joints from A down to base_link (fixed)
};

UrdfPath urdfPath(const XmlNode& root, const ChainDescription& chain) {
  std::map<std::string, const XmlNode*> by_child;
  for (const XmlNode* j : root.childrenNamed("joint")) {
    if (const XmlNode* c = j->child("child")) by_child[c->str("link", "")] = j;
  }
  const auto parentOf = [&](const XmlNode* j) {
    const XmlNode* p = j->child("parent");
    return p ? p->str("link", "") : std::string();
  };
  // base_link's ancestors (itself first) and the joints above each
  std::vector<std::string> base_up{chain.base_link};
  std::vector<const XmlNode*> base_joints;
  while (by_child.count(base_up.back()) && base_up.size() <= by_child.size() + 1) {
    base_joints.push_back(by_child[base_up.back()]);
    base_up.push_back(parentOf(base_joints.back()));
  }
  UrdfPath path;
  std::string link = chain.tip_link;
  while (std::find(base_up.begin(), base_up.end(), link) == base_up.end()) {
    const auto it = by_child.find(link);
    if (it == by_child.end() || path.down.size() > by_child.size())
      root.fail("no joint chain from '" + chain.base_link + "' to '" + chain.tip_link + "'");
    path.down.insert(path.down.begin(), it->second);
    link = parentOf(it->second);
  }
  const size_t a =
      static_cast<size_t>(std::find(base_up.begin(), base_up.end(), link) - base_up.begin());
  for (size_t k = a; k-- > 0;) path.to_base.push_back(base_joints[k]);
  if (path.down.empty())
    root.fail("'" + chain.tip_link + "' is not below '" + chain.base_link + "'");
  return path;
}

/// A joint's URDF origin (identity without <origin>).
Pose originOf(const XmlNode& joint) {
  Pose T = Pose::Identity();
  if (const XmlNode* o = joint.child("origin")) {
    const Vec3 rpy = o->vec3("rpy", Vec3::Zero());
    T.linear() = rotationFromRpy(rpy.x(), rpy.y(), rpy.z());
    T.translation() = o->vec3("xyz", Vec3::Zero());
  }
  return T;
}

/// Left and right factors of each URDF joint (by name) that carry the calibration.
struct OriginEdit {
  Pose left{Pose::Identity()};
  Pose right{Pose::Identity()};
  const XmlNode* joint{nullptr};
};

std::map<std::string, OriginEdit> originEdits(const std::string& path, const UrdfPath& urdf,
                                              const ChainDescription& chain,
                                              const GeometryCalibration& cal) {
  const std::vector<const XmlNode*>& joints = urdf.down;
  std::map<std::string, OriginEdit> edits;
  for (const XmlNode* j : joints) edits[j->str("name")].joint = j;
  for (size_t i = 0; i < 6; ++i) {
    const auto it = edits.find(chain.joints[i].name);
    if (it == edits.end())
      throw InputError(path, 0, "joint '" + chain.joints[i].name + "' is not on the chain");
    it->second.right = it->second.right * cal.joints[i].transform();
  }
  // E_base acts in base_link's frame B: in A it is T_A_B · E_base · T_A_B⁻¹
  Pose T_A_B = Pose::Identity();
  for (const XmlNode* j : urdf.to_base) T_A_B = T_A_B * originOf(*j);
  OriginEdit& first = edits[joints.front()->str("name")];
  first.left = T_A_B * cal.base.transform() * T_A_B.inverse() * first.left;
  const XmlNode& last = *joints.back();
  if (!cal.tool.isZero()) {
    if (last.str("name") == chain.joints[5].name) {
      throw InputError(path, last.line,
                       "flange_link '" + chain.tip_link +
                           "' is joint 6's own link: a tool (flange) error needs a fixed joint "
                           "after joint 6 to carry it");
    }
    edits[last.str("name")].right = edits[last.str("name")].right * cal.tool.transform();
  }
  return edits;
}

std::string shortest(double v) {
  if (v == 0.0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return {buf, r.ptr};
}

std::string triple(const Vec3& v) {
  return shortest(v.x()) + " " + shortest(v.y()) + " " + shortest(v.z());
}

int lineAt(const std::string& s, std::size_t pos) {
  return 1 + static_cast<int>(
                 std::count(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

/// Start of the `<name` tag (followed by space, '/' or '>') at or after `from`, comments skipped;
/// npos when none before `limit`.
std::size_t nextTag(const std::string& s, const std::string& name, std::size_t from,
                    std::size_t limit) {
  std::size_t i = from;
  while ((i = s.find('<', i)) != std::string::npos && i < limit) {
    if (s.compare(i, 4, "<!--") == 0) {
      const std::size_t e = s.find("-->", i + 4);
      if (e == std::string::npos) return std::string::npos;
      i = e + 3;
      continue;
    }
    const std::size_t after = i + 1 + name.size();
    if (s.compare(i + 1, name.size(), name) == 0 && after < s.size() &&
        (std::isspace(static_cast<unsigned char>(s[after])) || s[after] == '/' || s[after] == '>'))
      return i;
    ++i;
  }
  return std::string::npos;
}

/// Sets attribute `name` of the tag [begin, end) (end: its '>' or '/>') to `value`.
void setAttribute(std::string& s, std::size_t begin, std::size_t& end, const std::string& name,
                  const std::string& value) {
  for (const char q : {'"', '\''}) {
    for (const char lead : {' ', '\t', '\n', '\r'}) {
      const std::string key = std::string(1, lead) + name + "=" + q;
      const std::size_t at = s.find(key, begin);
      if (at == std::string::npos || at >= end) continue;
      const std::size_t v0 = at + key.size();
      const std::size_t v1 = s.find(q, v0);
      s.replace(v0, v1 - v0, value);
      end = end + value.size() - (v1 - v0);
      return;
    }
  }
  const std::string text = " " + name + "=\"" + value + "\"";
  s.insert(end, text);
  end += text.size();
}

/// Rewrites the origin of joint `name` to T.
void writeOrigin(std::string& s, const std::string& path, const std::string& name, const Pose& T) {
  const std::string xyz = triple(T.translation());
  const std::string rpy = triple(rpyFromRotation(T.linear()));
  std::size_t j = 0;
  while ((j = nextTag(s, "joint", j, s.size())) != std::string::npos) {
    const std::size_t close = s.find('>', j);
    const std::string tag = s.substr(j, close - j);
    // a kinematic joint (a <transmission>'s <joint name> has no type)
    if (tag.find("type=") != std::string::npos &&
        (tag.find("name=\"" + name + "\"") != std::string::npos ||
         tag.find("name='" + name + "'") != std::string::npos))
      break;
    j = close;
  }
  if (j == std::string::npos) throw InputError(path, 0, "joint '" + name + "' not found");
  const std::size_t body = s.find('>', j) + 1;
  const std::size_t end_joint = s.find("</joint>", body);
  if (end_joint == std::string::npos)
    throw InputError(path, lineAt(s, j), "<joint name=\"" + name + "\"> has no </joint>");
  const std::size_t o = nextTag(s, "origin", body, end_joint);
  if (o == std::string::npos) {
    s.insert(body, "<origin xyz=\"" + xyz + "\" rpy=\"" + rpy + "\"/>");
    return;
  }
  std::size_t end = s.find('>', o);
  if (s[end - 1] == '/') --end;
  setAttribute(s, o, end, "xyz", xyz);
  setAttribute(s, o, end, "rpy", rpy);
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the URDF");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::string calibratedUrdf(const std::string& urdf_path, const ChainDescription& nominal,
                           const GeometryCalibration& cal) {
  const XmlNode root = loadXmlFile(urdf_path);
  const UrdfPath path = urdfPath(root, nominal);
  std::string text = readText(urdf_path);
  for (const auto& [name, e] : originEdits(urdf_path, path, nominal, cal)) {
    if (e.left.isApprox(Pose::Identity(), 0.0) && e.right.isApprox(Pose::Identity(), 0.0))
      continue;  // unchanged joints keep their text
    writeOrigin(text, urdf_path, name, e.left * originOf(*e.joint) * e.right);
  }
  return text;
}

}  // namespace roprec
