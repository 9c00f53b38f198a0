// The cell's <process> (compensator/process/process_spec.hpp): defaults and units, overrides,
// the cutting length, and bad or implausible values named at their line.
#include "compensator/process/process_spec.hpp"

#include <gtest/gtest.h>

#include <string>
#include "compensator/precision/cell.hpp"
#include "compensator/support/error.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

ProcessSpec parse(const std::string& xml) { return parseProcess(parseXmlText(xml, "cell.xml")); }

/// Parses and expects an InputError at `line` whose message contains `what`.
void expectError(const std::string& xml, int line, const std::string& what) {
  try {
    parse(xml);
    ADD_FAILURE() << "no error for:\n" << xml;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "cell.xml");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

const char* const kDrilling =
    "<process type=\"drilling\">\n"
    "  <drill diameter_mm=\"10\" point_angle_deg=\"118\" helix_angle_deg=\"30\" web_mm=\"1.6\"/>\n"
    "  <cut feed_mm_per_rev=\"0.2\" spindle_rpm=\"3000\"/>\n"
    "  <material name=\"Al 6061-T6\"/>\n"
    "</process>\n";

TEST(ProcessSpec, DrillingDefaultsAndUnits) {
  const ProcessSpec s = parse(kDrilling);
  ASSERT_EQ(s.type, ProcessType::kDrilling);
  const DrillingSpec& d = s.drilling;
  EXPECT_DOUBLE_EQ(d.geometry.diameter, 10e-3);
  EXPECT_NEAR(d.geometry.point_angle, 118 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(d.geometry.web_thickness, 1.6e-3);
  EXPECT_NEAR(d.geometry.chisel_angle, 125 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(d.feed, 0.2e-3);
  EXPECT_DOUBLE_EQ(d.hole_depth, 20e-3);
  EXPECT_TRUE(d.working_angles);
  EXPECT_EQ(d.material->name, "Al 6061-T6");
  EXPECT_FALSE(d.runout_given);
  EXPECT_NEAR(d.geometry.runout, 0.25e-3 * 30e-3, 1e-15);  // default: 0.25 µm/mm × 3 Dc
  EXPECT_DOUBLE_EQ(d.deviation.runout, d.geometry.runout);
}

TEST(ProcessSpec, CoefficientAndDeviationOverrides) {
  const ProcessSpec s = parse(
      "<process type=\"drilling\">\n"
      "  <drill diameter_mm=\"8\" runout_mm=\"0.01\" tool_material=\"hss\" angle_law=\"paper\"/>\n"
      "  <cut feed_mm_per_rev=\"0.1\" depth_mm=\"12\" through=\"true\"/>\n"
      "  <material name=\"A356\"/>\n"
      "  <coefficients kst0_N_mm2=\"900\" ksa0_N_mm2=\"650\" bt_per_deg=\"-0.012\" "
      "chisel_model=\"pressure\"\n"
      "                chisel_pressure_ratio=\"4\" source=\"shop test 2026\"/>\n"
      "  <machining_deviation axis_tilt_deg=\"0.05\" spindle_compliance_um_per_N=\"0.1\"/>\n"
      "</process>\n");
  const DrillingSpec& d = s.drilling;
  EXPECT_EQ(d.law, AngleLaw::kPaperProportional);
  EXPECT_FALSE(d.carbide);
  EXPECT_DOUBLE_EQ(d.deviation.youngs_modulus, 210e9);
  EXPECT_DOUBLE_EQ(d.geometry.runout, 0.01e-3);
  EXPECT_DOUBLE_EQ(d.deviation.runout, 0.01e-3);
  EXPECT_TRUE(d.through);
  EXPECT_DOUBLE_EQ(d.coeff.tangential.k0, 900e6);
  EXPECT_DOUBLE_EQ(d.coeff.axial.k0, 650e6);
  EXPECT_NEAR(d.coeff.tangential.b * kDeg, -0.012, 1e-15);
  EXPECT_EQ(d.coeff.chisel.kind, ChiselModelKind::kPressure);
  EXPECT_EQ(d.coeff_source, "shop test 2026");
  EXPECT_NEAR(d.deviation.axis_tilt, 0.05 * kDeg, 1e-15);
  EXPECT_NEAR(d.deviation.spindle_compliance, 0.1e-6, 1e-18);
}

// Overrides apply per diameter (docs/process.md §5.7): the drill's own stick-out only at its
// diameter, a general <machining_deviation> at every diameter, a diameter_mm list only at the
// diameters it names (and over the general one); the runout default follows the stick-out.
TEST(ProcessSpec, MachiningDeviationOverridesApplyToTheDiametersTheyName) {
  const ProcessSpec s = parse(
      "<process type=\"drilling\">\n"
      "  <drill diameter_mm=\"10\" stickout_mm=\"50\"/>\n"
      "  <cut feed_mm_per_rev=\"0.2\"/>\n"
      "  <material name=\"Al 6061-T6\"/>\n"
      "  <machining_deviation spindle_compliance_um_per_N=\"0.2\"/>\n"
      "  <machining_deviation diameter_mm=\"8 12\" stickout_mm=\"40\" "
      "spindle_compliance_um_per_N=\"0.1\"/>\n"
      "</process>\n");
  const DrillingSpec& d = s.drilling;
  EXPECT_DOUBLE_EQ(d.deviation.stickout, 50e-3);  // <drill stickout_mm> at Dc 10
  EXPECT_NEAR(d.deviation.runout, 0.25e-3 * 50e-3, 1e-15);
  EXPECT_NEAR(d.deviation.spindle_compliance, 0.2e-6, 1e-18);
  for (double D : {8e-3, 12e-3}) {
    const MachiningDeviationParams p = machiningDeviationAt(d, D);
    EXPECT_DOUBLE_EQ(p.stickout, 40e-3) << D;
    EXPECT_NEAR(p.runout, 0.25e-3 * 40e-3, 1e-15) << D;
    EXPECT_NEAR(p.spindle_compliance, 0.1e-6, 1e-18) << D;
    EXPECT_NE(p.stickout_source.find("line 6"), std::string::npos) << p.stickout_source;
  }
  const MachiningDeviationParams p6 = machiningDeviationAt(d, 6e-3);  // named by none
  EXPECT_NEAR(p6.stickout, 18e-3, 1e-15);                             // default 3 Dc
  EXPECT_NEAR(p6.spindle_compliance, 0.2e-6, 1e-18);                  // the general override
  EXPECT_NEAR(p6.axis_lever, 6e-3, 1e-15);
}

TEST(ProcessSpec, CuttingLengthIsTheFluteLengthElseTheStickOutElseTheThreeDiameterEstimate) {
  const DrillingSpec plain = parse(kDrilling).drilling;  // Ø10, nothing stated
  const CuttingLength est = cuttingLengthAt(plain, 10e-3);
  EXPECT_NEAR(est.length, 30e-3, 1e-15);
  EXPECT_EQ(est.source.rfind("estimate: stick-out 3 Dc", 0), 0u) << est.source;
  EXPECT_NEAR(cuttingLengthAt(plain, 6e-3).length, 18e-3, 1e-15);
  const auto with = [](const std::string& attrs) {
    return parse("<process type=\"drilling\">\n  <drill diameter_mm=\"10\" " + attrs +
                 "/>\n  <cut feed_mm_per_rev=\"0.2\"/>\n  <material name=\"Al 6061-T6\"/>\n"
                 "</process>\n")
        .drilling;
  };
  const DrillingSpec stick = with("stickout_mm=\"50\"");
  EXPECT_NEAR(cuttingLengthAt(stick, 10e-3).length, 50e-3, 1e-15);
  EXPECT_EQ(cuttingLengthAt(stick, 10e-3).source, "cell <drill stickout_mm>");
  const DrillingSpec flute = with("stickout_mm=\"50\" flute_length_mm=\"43\"");
  EXPECT_NEAR(flute.drill_flute_length.value_or(0), 43e-3, 1e-15);
  EXPECT_NEAR(cuttingLengthAt(flute, 10e-3).length, 43e-3, 1e-15);
  EXPECT_EQ(cuttingLengthAt(flute, 10e-3).source, "cell <drill flute_length_mm>");
  // the flute length is the drill's own: another diameter keeps its estimate
  EXPECT_NEAR(cuttingLengthAt(flute, 6e-3).length, 18e-3, 1e-15);
  // flutes longer than the stick-out: the part inside the holder does not cut
  const DrillingSpec held = with("stickout_mm=\"40\" flute_length_mm=\"60\"");
  EXPECT_NEAR(cuttingLengthAt(held, 10e-3).length, 40e-3, 1e-15);
  EXPECT_NE(cuttingLengthAt(held, 10e-3).source.find("flutes inside the holder"),
            std::string::npos);
  expectError(
      "<process type=\"drilling\">\n  <drill diameter_mm=\"10\" flute_length_mm=\"5\"/>\n"
      "  <cut feed_mm_per_rev=\"0.2\"/>\n  <material name=\"Al 6061-T6\"/>\n</process>\n",
      2, "flute_length_mm");
}

TEST(ProcessSpec, MachiningDeviationCoverageFactorIsRefused) {
  expectError(
      "<process type=\"drilling\">\n"
      "  <drill diameter_mm=\"10\"/>\n"
      "  <cut feed_mm_per_rev=\"0.2\"/>\n"
      "  <material name=\"Al 6061-T6\"/>\n"
      "  <machining_deviation k=\"2\"/>\n"
      "</process>\n",
      5, "2-D radial");
  expectError(
      "<process type=\"drilling\">\n"
      "  <drill diameter_mm=\"10\"/>\n"
      "  <cut feed_mm_per_rev=\"0.2\"/>\n"
      "  <material name=\"Al 6061-T6\"/>\n"
      "  <machining_deviation diameter_mm=\"8 x\"/>\n"
      "</process>\n",
      5, "diameter_mm");
}

TEST(ProcessSpec, MillingAndWrench) {
  const ProcessSpec m = parse(
      "<process type=\"milling\">\n"
      "  <mill diameter_mm=\"10\" teeth=\"3\" helix_angle_deg=\"30\" runout_mm=\"0.005\"/>\n"
      "  <cut ap_mm=\"5\" ae_mm=\"2\" fz_mm=\"0.1\" mode=\"down\"/>\n"
      "  <material name=\"Al 7075-T6\"/>\n"
      "  <coupling compliance_um_per_N=\"1 0 0 0 2 0 0 0 3\" relaxation=\"0.5\"/>\n"
      "</process>\n");
  ASSERT_EQ(m.type, ProcessType::kMilling);
  EXPECT_EQ(m.milling.tool.teeth, 3);
  EXPECT_EQ(m.milling.cut.mode, MillingMode::kDown);
  EXPECT_DOUBLE_EQ(m.milling.cut.ae, 2e-3);
  ASSERT_TRUE(m.milling.compliance.has_value());
  EXPECT_DOUBLE_EQ((*m.milling.compliance)(1, 1), 2e-6);
  EXPECT_DOUBLE_EQ(m.milling.coupling.relaxation, 0.5);
  const ProcessSpec w =
      parse("<process type=\"wrench\" force_N=\"10 -20 -1500\" torque_Nm=\"0 0 -3\"/>");
  ASSERT_EQ(w.type, ProcessType::kWrench);
  EXPECT_EQ(w.wrench.force, Vec3(10, -20, -1500));
  EXPECT_EQ(w.wrench.torque, Vec3(0, 0, -3));
}

TEST(ProcessSpec, BadInputNamesTheLine) {
  auto with = [](const std::string& drill, const std::string& cut, const std::string& mat) {
    return "<process type=\"drilling\">\n  " + drill + "\n  " + cut + "\n  " + mat +
           "\n</process>\n";
  };
  const std::string d = "<drill diameter_mm=\"10\"/>";
  const std::string c = "<cut feed_mm_per_rev=\"0.2\"/>";
  const std::string m = "<material name=\"Al 6061-T6\"/>";
  expectError(with(d, "<cut feed_mm_per_rev=\"-0.2\"/>", m), 3, "feed_mm_per_rev must be > 0");
  expectError(with("<drill diameter_mm=\"10\" point_angle_deg=\"55\"/>", c, m), 2, "point angle");
  expectError(with("<drill diameter_mm=\"10\" point_angle_deg=\"180\"/>", c, m), 2, "point angle");
  expectError(with("<drill diameter_mm=\"10\" web_mm=\"12\"/>", c, m), 2, "wider than the drill");
  expectError(with(d, c, "<material name=\"unobtainium\"/>"), 4, "unknown material 'unobtainium'");
  expectError(with("<drill diameter_mm=\"10\" diamter=\"3\"/>", c, m), 2,
              "unknown attribute 'diamter'");
  expectError(with("<drill diameter_mm=\"-10\"/>", c, m), 2, "diameter_mm must be > 0");
  expectError("<process type=\"drilling\">\n  <cut feed_mm_per_rev=\"0.2\"/>\n</process>", 1,
              "<drill>");
  expectError(
      "<process type=\"milling\">\n <mill diameter_mm=\"10\"/>\n <cut ap_mm=\"5\" ae_mm=\"12\" "
      "fz_mm=\"0.1\"/>\n"
      " <material name=\"Al 6061-T6\"/>\n</process>",
      3, "ae_mm must be <= the cutter diameter");
  expectError(
      "<process type=\"milling\">\n <mill diameter_mm=\"10\"/>\n <cut ap_mm=\"5\" ae_mm=\"2\" "
      "fz_mm=\"0.1\" "
      "mode=\"sideways\"/>\n <material name=\"Al 6061-T6\"/>\n</process>",
      3, "mode must be");
  expectError("<process type=\"wrench\" force_N=\"1 2\"/>", 1, "needs 3 numbers");
}

TEST(ProcessSpec, SampleCellsParseWithoutLoadingTheRobot) {
  for (const char* name :
       {"alu-drilling-6061.xml", "alu-drilling-7075-dc8.xml", "alu-milling-7075.xml"}) {
    const CellSpec cell = loadCell(test::sourceDir() + "/samples/cells/" + name);
    ASSERT_TRUE(cell.has_process) << name;
    EXPECT_EQ(cell.robot.robot, "kuka-kr120-r2500-pro");
    EXPECT_NO_THROW(parseProcess(cell.process)) << name;
  }
}

TEST(ProcessSpec, CalibratedCopyKeepsTheRestOfTheCell) {
  const std::string text =
      test::readFile(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml");
  DrillingCoefficients c = findMaterial("Al 6061-T6")->drilling;
  c.tangential.k0 = 1091.25e6;
  c.axial.k0 = 760.5e6;
  const std::string out = cellWithCalibratedCoefficients(text, "x.xml", c, "unit test");
  const XmlNode root = parseXmlText(out, "out.xml");
  const XmlNode* k = root.child("process")->child("coefficients");
  ASSERT_NE(k, nullptr);
  EXPECT_DOUBLE_EQ(k->number("kst0_N_mm2"), 1091.25);
  EXPECT_DOUBLE_EQ(k->number("ksa0_N_mm2"), 760.5);
  EXPECT_EQ(root.child("robot")->str("ref"), "kuka-kr120-r2500-pro");
  EXPECT_EQ(root.child("process")->child("material")->str("name"), "Al 6061-T6");
  const ProcessSpec s = parseProcess(*root.child("process"));
  EXPECT_DOUBLE_EQ(s.drilling.coeff.tangential.k0, 1091.25e6);
}

TEST(ProcessSpec, DrillStickoutMustBeAtLeastTheDiameter) {
  const auto spec = [](const std::string& stickout) {
    return "<process type=\"drilling\">\n"
           "  <drill diameter_mm=\"10\" stickout_mm=\"" +
           stickout +
           "\"/>\n"
           "  <cut feed_mm_per_rev=\"0.2\" spindle_rpm=\"3000\"/>\n"
           "  <material name=\"Al 6061-T6\"/>\n"
           "</process>\n";
  };
  EXPECT_NO_THROW(parseProcess(parseXmlText(spec("34"), "cell.xml")));
  for (const char* bad : {"1e-300", "5", "1e300"}) {
    try {
      (void)parseProcess(parseXmlText(spec(bad), "cell.xml"));
      ADD_FAILURE() << "stickout " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 2);
      EXPECT_NE(std::string(e.what()).find("stickout_mm"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("plausible range 10 .. 1000"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace roprec
