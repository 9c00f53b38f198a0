// Writing the <calibration> block back into a card's text: replaced or inserted, every other byte
// unchanged, and what is written loads back.
#include "compensator/precision/card_writer.hpp"

#include <gtest/gtest.h>

#include "compensator/robot/geometry_calibration.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_node.hpp"

namespace roprec {
namespace {

const std::array<std::string, 6> kNames{"a1", "a2", "a3", "a4", "a5", "a6"};

GeometryCalibration someCalibration() {
  GeometryCalibration c;
  c.source = "tracker \"T1\" & fit";
  c.date = "2026-11-28";
  c.measurements = 12;
  c.residual_rms = 7.5e-6;
  c.joints[1].dxyz = Vec3(1e-4, -2e-4, 0.0);
  c.joints[1].drpy = Vec3(0.0, 3e-4, 0.0);
  c.joints[1].sigma_xyz = Vec3(1e-5, 1e-5, 1e-5);
  c.tool.dxyz = Vec3(0.0, 0.0, 2.5e-4);
  return c;
}

TEST(CardWriter, CalibrationBlockIsInsertedBeforeRobotEndAndLoadsBack) {
  const std::string card = "<robot>\n  <!-- <calibration source=\"old\"/> -->\n  <x/>\n</robot>\n";
  const std::string block = calibrationXml(someCalibration(), kNames);
  const std::string out = replaceCardCalibration(card, "card.xml", block);
  EXPECT_EQ(out,
            "<robot>\n  <!-- <calibration source=\"old\"/> -->\n  <x/>\n" + block + "</robot>\n");
  const XmlNode root = parseXmlText(out, "card.xml");
  const GeometryCalibration back = parseCalibration(*root.child("calibration"), kNames);
  EXPECT_EQ(back.source, someCalibration().source);
  EXPECT_EQ(back.measurements, 12);
  EXPECT_NEAR(back.joints[1].drpy.y(), 3e-4, 1e-19);
  EXPECT_NEAR(back.joints[1].sigma_xyz.z(), 1e-5, 1e-19);
  EXPECT_NEAR(back.tool.dxyz.z(), 2.5e-4, 1e-19);
  EXPECT_TRUE(back.joints[0].isZero());
}

TEST(CardWriter, CalibrationBlockReplacesTheOldOneWholeLines) {
  const std::string head = "<robot>\r\n  <x a='1'/>\r\n";
  const std::string tail = "  <y/>\r\n</robot>";
  for (const std::string old : {"  <calibration source=\"a\"/>\r\n",
                                "  <calibration source=\"a\">\r\n    <tool xyz_mm=\"0 0 1\"/>\r\n"
                                "  </calibration>\r\n"}) {
    const std::string out = replaceCardCalibration(head + old + tail, "c.xml", "NEW\n");
    EXPECT_EQ(out, head + "NEW\n" + tail);
  }
}

TEST(CardWriter, UnterminatedCalibrationFailsAtItsLine) {
  try {
    replaceCardCalibration("<robot>\n<calibration source='a'>\n<tool/>\n</robot>", "c.xml", "");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
  }
  EXPECT_THROW(replaceCardCalibration("<robot/>", "c.xml", "x"), InputError);
}

}  // namespace
}  // namespace roprec
