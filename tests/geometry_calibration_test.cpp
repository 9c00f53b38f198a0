// The calibrated (real) chain against an independent reference: KDL on a URDF whose joint origins
// were perturbed in the text (origin' = origin · E, composed with KDL's own RPY), the base error
// composed on the left and the tool error appended as a fixed KDL segment.
#include "compensator/robot/geometry_calibration.hpp"

#include <gtest/gtest.h>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <random>

#include "compensator/robot/model.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_node.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// A random error in the ranges of a real uncalibrated arm: ±0.4 mm, ±0.6 mrad per component.
FrameError randomError(std::mt19937& rng) {
  std::uniform_real_distribution<double> mm(-0.4e-3, 0.4e-3);
  std::uniform_real_distribution<double> mrad(-0.6e-3, 0.6e-3);
  FrameError e;
  e.dxyz = Vec3(mm(rng), mm(rng), mm(rng));
  e.drpy = Vec3(mrad(rng), mrad(rng), mrad(rng));
  e.sigma_xyz = Vec3(1e-5, 2e-5, 3e-5);
  e.sigma_rpy = Vec3(1e-5, 2e-5, 3e-5);
  return e;
}

GeometryCalibration randomCalibration(unsigned seed) {
  std::mt19937 rng(seed);
  GeometryCalibration cal;
  for (FrameError& j : cal.joints) j = randomError(rng);
  cal.base = randomError(rng);
  cal.tool = randomError(rng);
  cal.source = "test: seeded random errors";
  cal.date = "2026-11-28";
  cal.measurements = 40;
  cal.residual_rms = 6e-6;
  return cal;
}

/// FK of the truth robot: KDL on the perturbed URDF, base error in front, tool error appended.
class KdlTruth {
 public:
  KdlTruth(const Robot& robot, const GeometryCalibration& cal, const std::string& tag)
      : chain_(test::kdlTruthGeometry(robot, cal, test::tempDir(tag))
                   .chain(robot.chain.base_link, robot.chain.tip_link)) {}
  [[nodiscard]] Pose fk(const Vec6& q) const {
    KDL::ChainFkSolverPos_recursive solver(chain_);
    KDL::JntArray jq(6);
    for (unsigned i = 0; i < 6; ++i) jq(i) = q[i];
    KDL::Frame F;
    EXPECT_GE(solver.JntToCart(jq, F), 0);
    return test::fromKdl(F);
  }

 private:
  KDL::Chain chain_;
};

Vec6 randomJoints(const ChainDescription& chain, std::mt19937& rng) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(i)];
    q[i] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
  }
  return q;
}

void expectSamePose(const Pose& a, const Pose& b, double tol_m, double tol_rad) {
  EXPECT_LT((a.translation() - b.translation()).norm(), tol_m);
  EXPECT_LT((a.linear() - b.linear()).norm(), tol_rad);
}

std::array<std::string, 6> jointNames(const Robot& r) {
  std::array<std::string, 6> n;
  for (size_t i = 0; i < 6; ++i) n[i] = r.card.joints[i].name;
  return n;
}

TEST(GeometryCalibration, CalibratedChainMatchesKdlOnPerturbedUrdfOfThreeVendors) {
  for (const char* name : {"kuka-kr120-r2500-pro", "abb-irb6700-200-260", "fanuc-r2000ic-165f"}) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot({name, "", ""});
    const GeometryCalibration cal = randomCalibration(31);
    const KdlTruth truth(robot, cal, std::string("geomcal-") + name);
    const ChainDescription real = calibratedChain(robot.chain, cal);
    std::mt19937 rng(7);
    double moved = 0;
    for (int k = 0; k < 20; ++k) {
      const Vec6 q = randomJoints(robot.chain, rng);
      expectSamePose(chainForwardKinematics(real, q), truth.fk(q), 1e-12, 1e-12);
      moved = std::max(moved, (chainForwardKinematics(real, q).translation() -
                               chainForwardKinematics(robot.chain, q).translation())
                                  .norm());
    }
    EXPECT_GT(moved, 5e-4);  // the errors are visible: the test could fail
  }
}

TEST(GeometryCalibration, NaturalCoordinateModelTakesTheCalibratedGeometry) {
  // the model's constants (link vectors, unit-vector angles, TCP) come from the real chain: its
  // FK equals the KDL truth
  for (const char* name : {"kuka-kr210-r2700-2", "fanuc-r2000ic-210f"}) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot({name, "", ""});
    const GeometryCalibration cal = randomCalibration(44);
    const KdlTruth truth(robot, cal, std::string("geomcal-nc-") + name);
    const nc::Model model = nc::buildModel(calibratedChain(robot.chain, cal));
    nc::Data data(model);
    std::mt19937 rng(3);
    for (int k = 0; k < 20; ++k) {
      const Vec6 q = randomJoints(robot.chain, rng);
      ASSERT_TRUE(nc::forwardKinematics(model, data, q).converged);
      expectSamePose(data.T_W_flange, truth.fk(q), 1e-11, 1e-11);
    }
  }
}

TEST(GeometryCalibration, ZeroOffsetIsTheRotationAboutTheJointAxis) {
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  GeometryCalibration cal;
  const double offset = 0.3e-3;  // rad about joint 3's axis
  cal.joints[2].drpy = robot.chain.joints[2].axis * offset;
  const Vec6 q = (Vec6() << 0.1, -1.2, 1.4, 0.3, 0.5, -0.2).finished();
  Vec6 q_shift = q;
  q_shift[2] += offset;
  // exact: the bundled axes are frame axes, so the rpy error is a pure rotation about the axis
  expectSamePose(chainForwardKinematics(calibratedChain(robot.chain, cal), q),
                 chainForwardKinematics(robot.chain, q_shift), 1e-12, 1e-12);
}

TEST(GeometryCalibration, CardBlockLoadsIntoRealChainAndRoundTripsInNativeUnits) {
  const Robot nominal = loadRobot({"abb-irb6700-200-260", "", ""});
  const GeometryCalibration cal = randomCalibration(5);
  const std::string card = test::cardWithCalibration(
      nominal, calibrationXml(cal, jointNames(nominal)), test::tempDir("geomcal-card"));
  const Robot robot = loadRobot({card, "", ""});
  ASSERT_TRUE(robot.card.calibration.has_value());
  const GeometryCalibration& got = *robot.card.calibration;
  EXPECT_EQ(got.source, cal.source);
  EXPECT_EQ(got.date, cal.date);
  EXPECT_EQ(got.measurements, 40);
  EXPECT_NEAR(got.residual_rms, 6e-6, 1e-18);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_LT((got.joints[i].dxyz - cal.joints[i].dxyz).norm(), 1e-18);
    EXPECT_LT((got.joints[i].drpy - cal.joints[i].drpy).norm(), 1e-18);
    EXPECT_LT((got.joints[i].sigma_rpy - cal.joints[i].sigma_rpy).norm(), 1e-18);
  }
  EXPECT_GT(got.line, 0);
  const KdlTruth truth(robot, cal, "geomcal-card-kdl");
  std::mt19937 rng(11);
  for (int k = 0; k < 10; ++k) {
    const Vec6 q = randomJoints(robot.chain, rng);
    expectSamePose(chainForwardKinematics(robot.real_chain, q), truth.fk(q), 1e-12, 1e-12);
    // the nominal chain stays the URDF's
    expectSamePose(chainForwardKinematics(robot.chain, q), chainForwardKinematics(nominal.chain, q),
                   0.0 + 1e-15, 1e-15);
  }
}

// The <covariance> element: the factor L written (9 significant digits) gives back Σ = L Lᵀ to
// 1e-8 of its largest entry, correlations included, with its parameters and the model error; a
// bad element fails at its line.
TEST(GeometryCalibration, CovarianceRoundTripsThroughItsCholeskyFactor) {
  const std::array<std::string, 6> names{"a1", "a2", "a3", "a4", "a5", "a6"};
  GeometryCalibration cal;
  cal.source = "test";
  cal.model_error = 3.5e-6;
  cal.covariance_parameters = {"base_x", "base_rz", "j1_x", "j1_rz", "j6_z", "tip_z"};
  std::mt19937 rng(4);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd A(6, 6);
  for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = n(rng);
  cal.covariance = 1e-8 * A * A.transpose();  // 0.1 mm / 0.1 mrad scale, strongly correlated
  cal.covariance.row(1) *= 0.5;
  cal.covariance.col(1) *= 0.5;
  const std::string xml = calibrationXml(cal, names);
  const GeometryCalibration got = parseCalibration(parseXmlText(xml, "card.xml"), names);
  EXPECT_EQ(got.covariance_parameters, cal.covariance_parameters);
  ASSERT_EQ(got.covariance.rows(), 6);
  EXPECT_LT((got.covariance - cal.covariance).cwiseAbs().maxCoeff(),
            1e-8 * cal.covariance.cwiseAbs().maxCoeff())
      << xml;
  EXPECT_NEAR(got.model_error, 3.5e-6, 1e-18);
  EXPECT_EQ(calibrationComponent("base_x"), 0);
  EXPECT_EQ(calibrationComponent("j1_x"), 6);
  EXPECT_EQ(calibrationComponent("j6_rz"), 41);
  EXPECT_EQ(calibrationComponent("tip_rz"), 47);
  EXPECT_EQ(calibrationComponent("j7_x"), -1);
  EXPECT_EQ(calibrationComponent("reg_tx"), -1);
  const auto lineOf = [&](const std::string& bad) {
    try {
      parseCalibration(parseXmlText(bad, "card.xml"), names);
    } catch (const InputError& e) {
      return e.line();
    }
    return -1;
  };
  // unknown parameter, one row missing, a row of the wrong length, a parameter twice
  EXPECT_EQ(lineOf("<calibration source=\"s\">\n<covariance parameters=\"j1_q\"><row "
                   "l=\"1\"/></covariance></calibration>"),
            2);
  EXPECT_EQ(lineOf("<calibration source=\"s\">\n\n<covariance parameters=\"j1_x j1_y\"><row "
                   "l=\"1\"/></covariance></calibration>"),
            3);
  EXPECT_EQ(lineOf("<calibration source=\"s\"><covariance parameters=\"j1_x j1_y\">\n<row "
                   "l=\"1\"/>\n<row l=\"1\"/></covariance></calibration>"),
            3);
  EXPECT_EQ(lineOf("<calibration source=\"s\">\n<covariance parameters=\"j1_x j1_x\"><row "
                   "l=\"1\"/><row l=\"1 1\"/></covariance></calibration>"),
            2);
}

TEST(GeometryCalibration, CardWithoutBlockHasRealChainEqualToNominal) {
  const Robot robot = loadRobot({"kuka-kr210-r2700-2", "", ""});
  EXPECT_FALSE(robot.card.calibration.has_value());
  const Vec6 q = (Vec6() << 0.3, -1.0, 1.2, 0.4, -0.6, 0.9).finished();
  EXPECT_TRUE(chainForwardKinematics(robot.real_chain, q)
                  .isApprox(chainForwardKinematics(robot.chain, q), 0.0));
}

TEST(GeometryCalibration, BadBlocksFailAtTheirLine) {
  const std::array<std::string, 6> names{"a1", "a2", "a3", "a4", "a5", "a6"};
  const auto parse = [&](const std::string& xml) {
    parseCalibration(parseXmlText(xml, "card.xml"), names);
  };
  EXPECT_THROW(parse("<calibration date=\"x\"/>"), InputError);  // no source
  EXPECT_THROW(parse("<calibration source=\"s\">\n<joint_origin joint=\"a7\"/></calibration>"),
               InputError);
  EXPECT_THROW(parse("<calibration source=\"s\"><joint_origin joint=\"a1\"/>\n"
                     "<joint_origin joint=\"a1\"/></calibration>"),
               InputError);
  EXPECT_THROW(parse("<calibration source=\"s\"><tool sigma_xyz_mm=\"0 -1 0\"/></calibration>"),
               InputError);
  EXPECT_THROW(parse("<calibration source=\"s\"><base xyz=\"0 0 1\"/></calibration>"), InputError);
  try {
    parse("<calibration source=\"s\">\n\n<joint_origin joint=\"a9\"/></calibration>");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
  }
}

}  // namespace
}  // namespace roprec
