#include "tests/support/kdl_support.hpp"

#include "plugin/api/card_tools.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>
#include <tinyxml2.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>

namespace roprec::test {

KDL::Frame toKdl(const Pose& T) {
  const Mat3& R = T.linear();
  return KDL::Frame(KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0),
                                  R(2, 1), R(2, 2)),
                    KDL::Vector(T.translation().x(), T.translation().y(), T.translation().z()));
}

Pose fromKdl(const KDL::Frame& F) {
  Pose T = Pose::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = F.M(r, c);
    T.translation()[r] = F.p(r);
  }
  return T;
}

KDL::Chain kdlChain(const std::string& urdf, const std::string& base, const std::string& tip,
                    const Pose& extra) {
  KDL::Tree tree;
  KDL::Chain chain;
  if (!kdl_parser::treeFromFile(urdf, tree)) {
    ADD_FAILURE() << "kdl_parser could not read " << urdf;
    return chain;
  }
  if (!tree.getChain(base, tip, chain)) {
    ADD_FAILURE() << "KDL has no chain " << base << " -> " << tip << " in " << urdf;
    return chain;
  }
  if (!extra.isApprox(Pose::Identity(), 0.0)) {
    chain.addSegment(KDL::Segment("roprec_extra", KDL::Joint(KDL::Joint::None), toKdl(extra)));
  }
  return chain;
}

namespace {
KDL::Vector kdlVector(const char* text) {
  double x = 0, y = 0, z = 0;
  if (text != nullptr) std::istringstream(text) >> x >> y >> z;
  return {x, y, z};
}
std::string text3(double a, double b, double c) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g", a, b, c);
  return buf;
}
}  // namespace

std::string perturbedUrdf(const std::string& urdf_path,
                          const std::vector<std::pair<std::string, Pose>>& joint_errors) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(urdf_path.c_str()) != tinyxml2::XML_SUCCESS) {
    ADD_FAILURE() << "cannot read " << urdf_path;
    return "";
  }
  for (const auto& [name, E] : joint_errors) {
    tinyxml2::XMLElement* joint = doc.RootElement()->FirstChildElement("joint");
    while (joint != nullptr && name != joint->Attribute("name"))
      joint = joint->NextSiblingElement("joint");
    if (joint == nullptr) {
      ADD_FAILURE() << "no joint " << name << " in " << urdf_path;
      continue;
    }
    tinyxml2::XMLElement* origin = joint->FirstChildElement("origin");
    if (origin == nullptr) origin = joint->InsertNewChildElement("origin");
    const KDL::Vector rpy = kdlVector(origin->Attribute("rpy"));
    const KDL::Frame O(KDL::Rotation::RPY(rpy.x(), rpy.y(), rpy.z()),
                       kdlVector(origin->Attribute("xyz")));
    const KDL::Frame P = O * toKdl(E);
    double r = 0, p = 0, y = 0;
    P.M.GetRPY(r, p, y);
    origin->SetAttribute("xyz", text3(P.p.x(), P.p.y(), P.p.z()).c_str());
    origin->SetAttribute("rpy", text3(r, p, y).c_str());
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

GeometryCalibration seededGeometryErrors(unsigned seed, double mm, double mrad) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> t(-mm * 1e-3, mm * 1e-3);
  std::uniform_real_distribution<double> r(-mrad * 1e-3, mrad * 1e-3);
  const auto error = [&] {
    FrameError e;
    e.dxyz = Vec3(t(rng), t(rng), t(rng));
    e.drpy = Vec3(r(rng), r(rng), r(rng));
    return e;
  };
  GeometryCalibration cal;
  for (FrameError& j : cal.joints) j = error();
  cal.base = error();
  cal.tool = error();
  cal.source = "test: seeded geometric errors";
  return cal;
}

Pose kdlErrorPose(const FrameError& e) {
  return fromKdl(KDL::Frame(KDL::Rotation::RPY(e.drpy.x(), e.drpy.y(), e.drpy.z()),
                            KDL::Vector(e.dxyz.x(), e.dxyz.y(), e.dxyz.z())));
}

KDL::Chain KdlTruthGeometry::chain(const std::string& base_link, const std::string& tip_link,
                                   const Pose& extra) const {
  KDL::Chain c;
  c.addSegment(KDL::Segment("truth_base_error", KDL::Joint(KDL::Joint::None), toKdl(base)));
  c.addChain(kdlChain(urdf, base_link, tip_link, tool));
  if (!extra.isApprox(Pose::Identity(), 0.0))
    c.addSegment(KDL::Segment("truth_extra", KDL::Joint(KDL::Joint::None), toKdl(extra)));
  return c;
}

KdlTruthGeometry kdlTruthGeometry(const Robot& robot, const GeometryCalibration& cal,
                                  const std::string& dir) {
  std::vector<std::pair<std::string, Pose>> errors;
  for (size_t i = 0; i < 6; ++i)
    errors.emplace_back(robot.chain.joints[i].name, kdlErrorPose(cal.joints[i]));
  KdlTruthGeometry g;
  g.urdf = dir + "/truth.urdf";
  writeFile(g.urdf, perturbedUrdf(robot.card.urdf_path, errors));
  g.base = kdlErrorPose(cal.base);
  g.tool = kdlErrorPose(cal.tool);
  return g;
}

std::string cardWithCalibration(const Robot& robot, const std::string& block,
                                const std::string& dir) {
  std::string text = readFile(robot.card.file);
  const std::string name = std::filesystem::path(robot.card.urdf_path).filename().string();
  const std::size_t u = text.find("urdf=\"" + name + "\"");
  if (u == std::string::npos)
    ADD_FAILURE() << "no urdf=\"" << name << "\" in " << robot.card.file;
  else
    text.replace(u, 8 + name.size(), "urdf=\"" + robot.card.urdf_path + "\"");
  text.insert(text.rfind("</robot>"), block);
  const std::string path = dir + "/robot.xml";
  writeFile(path, text);
  return path;
}

KDL::Chain kdlExportedChain(const std::string& card_path, const std::string& dir,
                            const Pose& extra) {
  const std::string urdf = dir + "/real.urdf";
  writeFile(urdf, api::cardExportUrdf(card_path));
  const Robot r = loadRobot({card_path, "", ""});
  return kdlChain(urdf, r.chain.base_link, r.chain.tip_link, extra);
}

Pose kdlPose(const KDL::Chain& chain, const Eigen::Matrix<double, 6, 1>& q) {
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::JntArray jq(chain.getNrOfJoints());
  for (unsigned i = 0; i < jq.rows() && i < 6; ++i) jq(i) = q[i];
  KDL::Frame F;
  EXPECT_GE(fk.JntToCart(jq, F), 0);
  return fromKdl(F);
}

Eigen::Matrix<double, 6, 1> kdlGravity(const KDL::Chain& chain,
                                       const Eigen::Matrix<double, 6, 1>& q) {
  KDL::ChainIdSolver_RNE rne(chain, KDL::Vector(0, 0, -9.80665));
  KDL::JntArray jq(6);
  KDL::JntArray z(6);
  KDL::JntArray out(6);
  for (unsigned i = 0; i < 6; ++i) jq(i) = q[i];
  KDL::Wrenches f(chain.getNrOfSegments(), KDL::Wrench::Zero());
  EXPECT_GE(rne.CartToJnt(jq, z, z, f, out), 0);
  Eigen::Matrix<double, 6, 1> t;
  for (unsigned i = 0; i < 6; ++i) t[i] = out(i);
  return t;
}

}  // namespace roprec::test
