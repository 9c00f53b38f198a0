/// URDF loading (compensator/robot/urdf_loader.cpp) against independent references: KDL's own URDF
/// parser (kdl_parser) on the real ROS-Industrial files of the corpus, a hand-composed product
/// of the literal origins of a small fixture, hand-computed combined inertials, and one test
/// per kind of bad input, through the library and through the CLI: near-miss names, absurd
/// origins, axes and joint limits, non-numeric or unphysical inertials are errors at their line.
#include <gtest/gtest.h>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include <algorithm>
#include <filesystem>
#include <random>
#include <regex>
#include <string>

#include "compensator/robot/chain.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "tests/support/input_errors.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

std::string fixture(const std::string& name) {
  return test::sourceDir() + "/tests/data/urdf_fixtures/" + name;
}
std::string bad(const std::string& name) {
  return test::sourceDir() + "/tests/data/urdf_bad/" + name;
}

Pose fromKdl(const KDL::Frame& F) {
  Pose T = Pose::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = F.M(r, c);
    T.translation()[r] = F.p(r);
  }
  return T;
}

/// FK of the KDL chain base -> tip built by kdl_parser from the same file.
struct KdlReference {
  KDL::Chain chain;
  bool ok{false};
  KdlReference(const std::string& urdf, const std::string& base, const std::string& tip) {
    KDL::Tree tree;
    ok = kdl_parser::treeFromFile(urdf, tree) && tree.getChain(base, tip, chain) &&
         chain.getNrOfJoints() == 6;
  }
  Pose fk(const Vec6& q) const {
    KDL::ChainFkSolverPos_recursive solver(chain);
    KDL::JntArray jq(6);
    for (unsigned i = 0; i < 6; ++i) jq(i) = q[i];
    KDL::Frame F;
    solver.JntToCart(jq, F);
    return fromKdl(F);
  }
};

Vec6 randomWithinLimits(const ChainDescription& c, std::mt19937& rng) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = c.joints[static_cast<size_t>(i)];
    q[i] = std::uniform_real_distribution<double>(std::max(j.lower, -2 * kPi),
                                                  std::min(j.upper, 2 * kPi))(rng);
  }
  return q;
}

double rotationError(const Pose& a, const Pose& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

/// chainForwardKinematics == KDL on 200 seeded random joint vectors; `pre` maps KDL's base into
/// ours.
void expectMatchesKdl(const ChainDescription& c, const KdlReference& ref, const Pose& pre,
                      unsigned seed) {
  ASSERT_TRUE(ref.ok) << c.file << " " << c.base_link << " -> " << c.tip_link;
  std::mt19937 rng(seed);
  for (int k = 0; k < 200; ++k) {
    const Vec6 q = randomWithinLimits(c, rng);
    const Pose ours = chainForwardKinematics(c, q);
    const Pose theirs = pre * ref.fk(q);
    ASSERT_LT((ours.translation() - theirs.translation()).norm(), 1e-12)
        << c.file << " q=" << q.transpose();
    ASSERT_LT(rotationError(ours, theirs), 1e-12) << c.file << " q=" << q.transpose();
  }
}

// ---------------------------------------------------------------- corpus (real URDFs)

TEST(UrdfLoader, EveryCorpusUrdfLoadsWithTheDefaultTipAndMatchesKdl) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "corpus absent";
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(corpus + "/urdf")) {
    if (e.path().extension() != ".urdf") continue;
    const std::string path = e.path().string();
    SCOPED_TRACE(path);
    const ChainDescription c = loadUrdfChain(path);
    EXPECT_EQ(c.base_link, "base_link");
    EXPECT_EQ(c.tip_link, "tool0");  // every ROS-Industrial support package defines tool0
    expectMatchesKdl(c, KdlReference(path, c.base_link, c.tip_link), Pose::Identity(),
                     7u + static_cast<unsigned>(n));
    ++n;
  }
  EXPECT_EQ(n, 6);
}

TEST(UrdfLoader, AbbIrb6640SideBranchIsNotPartOfTheChain) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "corpus absent";
  const std::string path = corpus + "/urdf/irb6640_185_280.urdf";
  for (const std::string tip : {"link_6", "tool0"}) {
    const ChainDescription c = loadUrdfChain(path, {"base_link", tip});
    for (int i = 0; i < 6; ++i)
      EXPECT_EQ(c.joints[static_cast<size_t>(i)].name, "joint_" + std::to_string(i + 1));
    expectMatchesKdl(c, KdlReference(path, "base_link", tip), Pose::Identity(), 11u);
  }
  // The balancing cylinder and piston (continuous, mimic) hang off link_1 and link_2; the chain
  // between link_1 and link_cylinder has one joint only: not a 6R chain.
  EXPECT_THROW((void)loadUrdfChain(path, {"base_link", "link_piston"}), InputError);
}

TEST(UrdfLoader, FanucWorldFrameAsBaseLink) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "corpus absent";
  const std::string path = corpus + "/urdf/r2000ic165f.urdf";
  const ChainDescription c = loadUrdfChain(path, {"base", "tool0"});
  EXPECT_EQ(c.base_link, "base");
  // `base` is a fixed child of base_link at (0, 0, 0.670) (literal value of the file):
  // T_base_tool0 = T_base_link_base^-1 * T_base_link_tool0 (KDL, base_link -> tool0).
  Pose T_bl_base = Pose::Identity();
  T_bl_base.translation() = Vec3(0, 0, 0.670);
  expectMatchesKdl(c, KdlReference(path, "base_link", "tool0"), T_bl_base.inverse(), 13u);
  // All-zero: the faceplate centre is at (312 + 1280 + 215, 0, 1075 + 225) mm in World.
  const Pose T0 = chainForwardKinematics(c, Vec6::Zero());
  EXPECT_LT((T0.translation() - Vec3(1.807, 0, 1.300)).norm(), 1e-12);
}

TEST(UrdfLoader, KukaNegativeAxes) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "corpus absent";
  const ChainDescription c = loadUrdfChain(corpus + "/urdf/kr120r2500pro.urdf", {"", "flange"});
  EXPECT_LT((c.joints[0].axis - Vec3(0, 0, -1)).norm(), 1e-15);
  EXPECT_LT((c.joints[3].axis - Vec3(-1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((c.joints[5].axis - Vec3(-1, 0, 0)).norm(), 1e-15);
  // Flange at all-zero: (350 + 1150 + 1000 + 215, 0, 675 - 41) mm. A1 = +90 deg turns clockwise
  // seen from above (axis -z): the flange goes to -y.
  Vec6 q = Vec6::Zero();
  EXPECT_LT((chainForwardKinematics(c, q).translation() - Vec3(2.715, 0, 0.634)).norm(), 1e-12);
  q[0] = kPi / 2;
  EXPECT_LT((chainForwardKinematics(c, q).translation() - Vec3(0, -2.715, 0.634)).norm(), 1e-12);
}

TEST(UrdfLoader, MissingInertialsAreReportedNotInvented) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "corpus absent";
  const ChainDescription c = loadUrdfChain(corpus + "/urdf/irb6640_185_280.urdf");
  EXPECT_FALSE(c.has_inertials);
  for (const Inertial& in : c.inertials) {
    EXPECT_FALSE(in.present);
    EXPECT_EQ(in.mass, 0.0);
  }
}

// ---------------------------------------------------------------- fixture with rpy origins

Pose originOf(double x, double y, double z, double r, double p, double yw) {
  Pose T = Pose::Identity();
  T.translation() = Vec3(x, y, z);
  // URDF rpy: fixed-axis roll about X, then pitch about Y, then yaw about Z: R = Rz(y) Ry(p) Rx(r).
  T.linear() = (Eigen::AngleAxisd(yw, Vec3::UnitZ()) * Eigen::AngleAxisd(p, Vec3::UnitY()) *
                Eigen::AngleAxisd(r, Vec3::UnitX()))
                   .toRotationMatrix();
  return T;
}
Pose rot(const Vec3& axis, double q) {
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(q, axis.normalized()).toRotationMatrix();
  return T;
}

/// The fixture's transform product, written out from the literal numbers of rpy_chain.urdf.
Pose handComposed(const Vec6& q, bool from_world, bool to_tcp) {
  const double h = kPi / 2;
  Pose T = from_world ? originOf(0.5, -0.2, 0.1, 0, 0, 0.7) : Pose::Identity();
  T = T * originOf(0.01, 0.02, 0.4, 0.1, -0.2, 0.3) * rot(Vec3(0, 0, -1), q[0]);
  T = T * originOf(0.3, 0.05, 0.2, h, 0, 0) * rot(Vec3(0, 0, 1), q[1]);
  T = T * originOf(0.9, 0, 0, 0, 0, -0.4) * originOf(0.05, 0.1, 0, 0.2, 0.3, -0.1) *
      rot(Vec3(0, -1, 0), q[2]);
  T = T * originOf(0.8, 0, 0.12, -0.25, 0.15, 0.05) * rot(Vec3(1, 1, 0), q[3]);
  T = T * originOf(0, 0, 0, 0, 0, -h) * rot(Vec3(0, 1, 0), q[4]);
  T = T * originOf(0.1, 0, 0, kPi, 0, 0) * rot(Vec3(-1, 0, 0), q[5]);
  T = T * originOf(0.05, 0.01, -0.02, 0, h, 0);
  if (to_tcp) T = T * originOf(0, 0, 0.25, 0.1, 0.2, 0.3);
  return T;
}

TEST(UrdfLoader, RpyOriginsFixedJointsAndObliqueAxesMatchTheHandComposedProduct) {
  const std::string path = fixture("rpy_chain.urdf");
  const ChainDescription def = loadUrdfChain(path);  // root `world`, default tip `flange`
  const ChainDescription named = loadUrdfChain(path, {"base_link", "tcp"});
  EXPECT_EQ(def.base_link, "world");
  EXPECT_EQ(def.tip_link, "flange");
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(def.joints[static_cast<size_t>(i)].name, "j" + std::to_string(i + 1));
    EXPECT_EQ(named.joints[static_cast<size_t>(i)].name, "j" + std::to_string(i + 1));
  }
  EXPECT_TRUE(def.joints[5].continuous);
  EXPECT_LT((def.joints[3].axis - Vec3(1, 1, 0).normalized()).norm(), 1e-15);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  for (int k = 0; k < 500; ++k) {
    Vec6 q;
    for (int i = 0; i < 6; ++i) q[i] = u(rng);
    for (const auto& [c, world, tcp] :
         {std::tuple{&def, true, false}, std::tuple{&named, false, true}}) {
      const Pose ours = chainForwardKinematics(*c, q);
      const Pose ref = handComposed(q, world, tcp);
      ASSERT_LT((ours.translation() - ref.translation()).norm(), 1e-13);
      ASSERT_LT(rotationError(ours, ref), 1e-13);
    }
  }
  // Also against KDL on the same file.
  expectMatchesKdl(named, KdlReference(path, "base_link", "tcp"), Pose::Identity(), 5u);
}

TEST(UrdfLoader, FixedLinksAreFoldedIntoTheBodyInertial) {
  const ChainDescription c = loadUrdfChain(fixture("rpy_chain.urdf"));
  // Body 1 = l1 (10 kg at (0.1, 0, 0.2), I = diag(1,2,3)) + l1_cover (2 kg, fixed at xyz (0.2 0
  // 0.1) rpy (0 0.5 0); its COM at (0, 0.3, 0) with rpy (0.3 0 0), I = diag(0.1, 0.2, 0.3)).
  const Inertial& b1 = c.inertials[0];
  EXPECT_TRUE(b1.present);
  EXPECT_DOUBLE_EQ(b1.mass, 12.0);
  const Mat3 R_cover = Eigen::AngleAxisd(0.5, Vec3::UnitY()).toRotationMatrix();
  const Vec3 c_cover = Vec3(0.2, 0, 0.1) + R_cover * Vec3(0, 0.3, 0);
  const Vec3 com = (10.0 * Vec3(0.1, 0, 0.2) + 2.0 * c_cover) / 12.0;
  EXPECT_LT((b1.com - com).norm(), 1e-15);
  // Parallel-axis theorem about the combined COM, written out term by term.
  const Mat3 R2 = R_cover * Eigen::AngleAxisd(0.3, Vec3::UnitX()).toRotationMatrix();
  const Vec3 d1 = Vec3(0.1, 0, 0.2) - com;
  const Vec3 d2 = c_cover - com;
  const Mat3 I = Vec3(1, 2, 3).asDiagonal().toDenseMatrix().eval() +
                 10.0 * (d1.squaredNorm() * Mat3::Identity() - d1 * d1.transpose()) +
                 R2 * Vec3(0.1, 0.2, 0.3).asDiagonal().toDenseMatrix() * R2.transpose() +
                 2.0 * (d2.squaredNorm() * Mat3::Identity() - d2 * d2.transpose());
  EXPECT_LT((b1.inertia - I).norm(), 1e-13);
  // Bodies without <inertial>: absent, and the chain says so.
  EXPECT_FALSE(c.inertials[1].present);
  EXPECT_EQ(c.inertials[1].mass, 0.0);
  EXPECT_FALSE(c.has_inertials);
}

// ---------------------------------------------------------------- bad input

struct BadCase {
  const char* file;
  int line;
  const char* words;  ///< a fragment the message must contain
};

void expectInputError(const std::string& path, const UrdfChainRequest& req, int line,
                      const std::string& words) {
  try {
    (void)loadUrdfChain(path, req);
    ADD_FAILURE() << path << ": no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(e.message().find(words), std::string::npos) << e.message();
  }
}

void expectCliError(const std::string& args, const std::string& path, int line,
                    const std::string& words) {
  const test::RunResult r = test::runRoprec(args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "");
  const std::string prefix = "roprec: error: " + path + ":" + std::to_string(line) + ":";
  EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << "stderr: " << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
}

std::string fkArgs(const std::string& path, const std::string& extra = "") {
  return "fk --robot '" + path + "' " + extra + " --joints \"0 0 0 0 0 0\"";
}

// Malformed XML: tinyxml2 reports the line of the unclosed <link name="l1"> (line 5).
constexpr BadCase kMalformed{"malformed.urdf", 5, "malformed XML"};
constexpr BadCase kLoop{"loop.urdf", 17, "loop"};
constexpr BadCase kLoopRoot{"loop_root.urdf", 17, "loop"};
constexpr BadCase kPrismatic{"prismatic.urdf", 13, "prismatic"};
constexpr BadCase kFiveDof{"five_dof.urdf", 9, "5 revolute joints"};
constexpr BadCase kNan{"nan_origin.urdf", 14, "nan"};
constexpr BadCase kMissing{"missing_attribute.urdf", 12, "type"};

TEST(UrdfLoaderBadInput, MalformedXml) {
  expectInputError(bad(kMalformed.file), {}, kMalformed.line, kMalformed.words);
}
TEST(UrdfLoaderBadInput, LoopSecondParent) {
  expectInputError(bad(kLoop.file), {}, kLoop.line, kLoop.words);
}
TEST(UrdfLoaderBadInput, LoopThroughTheRoot) {
  expectInputError(bad(kLoopRoot.file), {}, kLoopRoot.line, kLoopRoot.words);
}
TEST(UrdfLoaderBadInput, PrismaticJointInTheChain) {
  expectInputError(bad(kPrismatic.file), {}, kPrismatic.line, kPrismatic.words);
}
TEST(UrdfLoaderBadInput, FiveDofChain) {
  expectInputError(bad(kFiveDof.file), {}, kFiveDof.line, kFiveDof.words);
}
TEST(UrdfLoaderBadInput, NanInOrigin) {
  expectInputError(bad(kNan.file), {}, kNan.line, kNan.words);
}
TEST(UrdfLoaderBadInput, MissingAttribute) {
  expectInputError(bad(kMissing.file), {}, kMissing.line, kMissing.words);
}
TEST(UrdfLoaderBadInput, UnknownBaseAndTipLinks) {
  // The <robot> element is on line 3 of the fixture.
  expectInputError(fixture("six_r.urdf"), {"no_such_base", ""}, 3, "no_such_base");
  expectInputError(fixture("six_r.urdf"), {"", "no_such_tip"}, 3, "no_such_tip");
}
TEST(UrdfLoaderBadInput, MissingFile) {
  EXPECT_THROW((void)loadUrdfChain(bad("does_not_exist.urdf")), InputError);
}
TEST(UrdfLoaderBadInput, UnknownRobotName) {
  try {
    (void)loadRobot({"no-such-robot", "", ""});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("no-such-robot"), std::string::npos);
    EXPECT_NE(e.message().find("kuka-kr120-r2500-pro"), std::string::npos)
        << "lists the bundled robots";
  }
}

// A URDF of 1,000 joints (a chain, and the same chain closed into a loop through the root) is
// answered with an error (exit 2 through the CLI): the loop check walks each link once and always
// ends (an unbounded walk round the loop would not end within the test's time limit).
TEST(UrdfLoaderBadInput, AThousandJointsAreCheckedInLinearTime) {
  const std::string dir = test::tempDir("urdf-1000");
  for (const bool loop : {false, true}) {
    std::string u = "<?xml version=\"1.0\"?>\n<robot name=\"long\">\n<link name=\"l0\"/>\n";
    for (int i = 1; i <= 1000; ++i) u += "<link name=\"l" + std::to_string(i) + "\"/>\n";
    for (int i = 1; i <= 1000; ++i) {
      u += "<joint name=\"j" + std::to_string(i) + "\" type=\"revolute\"><parent link=\"l" +
           std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) +
           "\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\" "
           "effort=\"0\"/></joint>\n";
    }
    if (loop) {
      u += "<joint name=\"jclose\" type=\"revolute\"><parent link=\"l1000\"/><child link=\"l0\"/>"
           "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" velocity=\"1\" effort=\"0\"/>"
           "</joint>\n";
    }
    u += "</robot>\n";
    const std::string path = dir + (loop ? "/loop.urdf" : "/chain.urdf");
    test::writeFile(path, u);
    try {
      (void)loadUrdfChain(path);
      ADD_FAILURE() << "a 1000-joint chain was loaded as a 6R robot";
    } catch (const InputError& e) {
      if (loop) {
        EXPECT_NE(e.message().find("kinematic loop"), std::string::npos) << e.message();
      }
    }
    const auto r = test::runRoprec(fkArgs(path));
    EXPECT_EQ(r.exit_code, 2) << r.err;
  }
}

// The same through the CLI (`roprec fk`): exit code 2, `roprec: error: FILE:LINE: ...`, no output.
TEST(UrdfLoaderBadInputCli, MalformedXml) {
  expectCliError(fkArgs(bad(kMalformed.file)), bad(kMalformed.file), kMalformed.line,
                 kMalformed.words);
}
TEST(UrdfLoaderBadInputCli, Loop) {
  expectCliError(fkArgs(bad(kLoop.file)), bad(kLoop.file), kLoop.line, kLoop.words);
}
TEST(UrdfLoaderBadInputCli, LoopThroughTheRoot) {
  expectCliError(fkArgs(bad(kLoopRoot.file)), bad(kLoopRoot.file), kLoopRoot.line, kLoopRoot.words);
}
TEST(UrdfLoaderBadInputCli, PrismaticJointInTheChain) {
  expectCliError(fkArgs(bad(kPrismatic.file)), bad(kPrismatic.file), kPrismatic.line,
                 kPrismatic.words);
}
TEST(UrdfLoaderBadInputCli, FiveDofChain) {
  expectCliError(fkArgs(bad(kFiveDof.file)), bad(kFiveDof.file), kFiveDof.line, kFiveDof.words);
}
TEST(UrdfLoaderBadInputCli, NanInOrigin) {
  expectCliError(fkArgs(bad(kNan.file)), bad(kNan.file), kNan.line, kNan.words);
}
TEST(UrdfLoaderBadInputCli, MissingAttribute) {
  expectCliError(fkArgs(bad(kMissing.file)), bad(kMissing.file), kMissing.line, kMissing.words);
}
TEST(UrdfLoaderBadInputCli, UnknownBaseAndTipLinks) {
  expectCliError(fkArgs(fixture("six_r.urdf"), "--base no_such_base"), fixture("six_r.urdf"), 3,
                 "no_such_base");
  expectCliError(fkArgs(fixture("six_r.urdf"), "--tip no_such_tip"), fixture("six_r.urdf"), 3,
                 "no_such_tip");
}
TEST(UrdfLoaderBadInputCli, UnknownRobotName) {
  const test::RunResult r = test::runRoprec("fk --robot no-such-robot --joints \"0 0 0 0 0 0\"");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("roprec: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("no-such-robot"), std::string::npos) << r.err;
}

namespace fs = std::filesystem;

std::string kukaUrdf() {
  return test::sourceDir() + "/robots/kuka-kr120-r2500-pro/kr120r2500pro.urdf";
}

/// The KUKA URDF with the first <limit lower="..."> replaced by `lower`; returns the line of the
/// <joint> element that carries it in *joint_line.
std::string urdfWithLowerLimit(const std::string& dir, const std::string& lower, int* joint_line) {
  std::string text = test::readFile(kukaUrdf());
  const std::size_t l = text.find("<limit lower=\"");
  const std::size_t v = l + std::string("<limit lower=\"").size();
  const std::size_t e = text.find('"', v);
  text.replace(v, e - v, lower);
  const std::size_t j = text.rfind("<joint", l);
  *joint_line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + j, '\n'));
  const std::string path = dir + "/bad_limit.urdf";
  test::writeFile(path, text);
  return path;
}

TEST(UrdfLoaderBadInput, AnAbsurdJointLimitIsRefusedAtTheJointLine) {
  const std::string dir = test::tempDir("range-urdf");
  int line = 0;
  const std::string path = urdfWithLowerLimit(dir, "-1e300", &line);
  try {
    (void)loadUrdfChain(path);
    FAIL() << "a joint limit of -1e300 rad was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find("out of range"), std::string::npos) << what;
    EXPECT_LT(what.size(), 400u) << what;  // the number in bounded %g, not 300 digits
  }
  // 10 turns is the limit; 9 turns still loads
  const std::string ok = urdfWithLowerLimit(dir, "-56.5", &line);
  EXPECT_NO_THROW((void)loadUrdfChain(ok));
}

// A non-numeric inertia must be an InputError at its line, not an exception thrown inside Eigen's
// comma initializer (whose destructor aborts in builds with assertions).
TEST(UrdfLoaderBadInput, ANonNumericInertiaIsAnInputErrorAtItsLine) {
  const std::string dir = test::tempDir("errloc_urdf");
  std::string urdf =
      test::readFile(test::sourceDir() + "/robots/kuka-kr120-r2500-pro/kr120r2500pro.urdf");
  const std::size_t at = urdf.find("iyz=\"");
  ASSERT_NE(at, std::string::npos);
  urdf.replace(at, 5, "iyz=\"i0");
  test::writeFile(dir + "/r.urdf", urdf);
  try {
    loadUrdfChain(dir + "/r.urdf", {"base_link", "flange"});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_GT(e.line(), 0) << e.what();
    EXPECT_NE(std::string(e.what()).find("iyz"), std::string::npos) << e.what();
  }
}

TEST(UrdfLoaderBadInput, InertialsMustBePhysical) {
  const std::string urdf = test::readFile(kukaUrdf());
  const std::regex mass("<mass value=\"([0-9.eE+-]+)\"\\s*/>");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(urdf, m, mass));
  const std::string dir = test::tempDir("strict-urdf");
  for (const char* value : {"-12", "nan"}) {
    SCOPED_TRACE(value);
    std::string text = urdf;
    text.replace(static_cast<std::size_t>(m.position(1)), static_cast<std::size_t>(m.length(1)),
                 value);
    test::writeFile(dir + "/r.urdf", text);
    EXPECT_THROW((void)loadUrdfChain(dir + "/r.urdf"), InputError);
  }
}

std::string urdfError(const std::string& anchor, const std::string& from, const std::string& to) {
  const std::string dir = test::editedKr120("kr120r2500pro.urdf", anchor, from, to);
  return test::inputErrorText([&] { (void)loadUrdfChain(dir + "/kr120r2500pro.urdf"); });
}

TEST(UrdfLoaderBadInput, NearMissNamesAndAbsurdOriginsAreErrorsAtTheirLine) {
  const std::string j2 = "<joint name=\"joint_a2\"";
  EXPECT_NE(urdfError(j2, "<origin xyz=", "<origin ryz=")
                .find(":122: unknown attribute 'ryz' on "
                      "<origin> (did you mean 'xyz'?)"),
            std::string::npos)
      << urdfError(j2, "<origin xyz=", "<origin ryz=");
  EXPECT_NE(urdfError(j2, "<axis xyz", "<axns xyz")
                .find(":123: unknown element <axns> in <joint> "
                      "(did you mean <axis>?)"),
            std::string::npos)
      << urdfError(j2, "<axis xyz", "<axns xyz");
  EXPECT_NE(urdfError(j2, "rpy=\"0 0 0\"", "rpy=\"1e300 0 0\"")
                .find(":122: <origin> rpy '1e300 0 0' is beyond 100 rad"),
            std::string::npos);
  EXPECT_NE(urdfError(j2, "xyz=\"0.350 0 0.675\"", "xyz=\"0.350 0 1e300\"")
                .find(":122: <origin> xyz '0.350 0 1e300' is beyond 100 m"),
            std::string::npos);
  EXPECT_NE(urdfError(j2, "<limit lower", "<limit lowr").find(":125: unknown attribute 'lowr'"),
            std::string::npos);
  EXPECT_NE(urdfError("<link", "<mass value=", "<mass valeu=")
                .find("unknown attribute 'valeu' on <mass> (did you mean 'value'?)"),
            std::string::npos);
  EXPECT_NE(urdfError("<link", "<inertial>", "<inertial><centre/>")
                .find("unknown element <centre> in <inertial>"),
            std::string::npos);
  // an axis component of 1e300 must not be normalised into another axis
  EXPECT_NE(urdfError(j2, "<axis xyz=\"0 1 0\"", "<axis xyz=\"0 1 1e300\"")
                .find(":123: joint 'joint_a2' axis xyz '0 1 1e300' is not a direction"),
            std::string::npos)
      << urdfError(j2, "<axis xyz=\"0 1 0\"", "<axis xyz=\"0 1 1e300\"");
  // The unmutated copy loads (the checks accept the bundled URDF).
  EXPECT_EQ(urdfError(j2, "<origin", "<origin"), "(accepted)");
}

}  // namespace
}  // namespace roprec
