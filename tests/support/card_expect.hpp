#pragma once
// The data-sheet header every bundled robot card carries, checked the same way for the first
// three robots (tests/robots_test.cpp) and the later ones (tests/bundled_robots_test.cpp).
#include <gtest/gtest.h>

#include "compensator/robot/robot_card.hpp"

namespace roprec::test {

struct CardHeader {
  const char* name;
  const char* vendor;
  const char* base_link;
  double payload_kg;
  double rp_mm;
  double j23_coupling;
};

/// Name, vendor, links, rated payload, repeatability, sources, gravity handling and the FANUC
/// J2/J3 coupling of a loaded card against its data sheet.
inline void expectDatasheetHeader(const RobotCard& c, const CardHeader& d) {
  EXPECT_EQ(c.name, d.name);
  EXPECT_EQ(vendorName(c.vendor), d.vendor);
  EXPECT_EQ(c.base_link, d.base_link);
  EXPECT_EQ(c.flange_link, "flange");
  EXPECT_DOUBLE_EQ(c.rated_payload_kg, d.payload_kg);
  EXPECT_DOUBLE_EQ(c.rp_mm, d.rp_mm);
  EXPECT_FALSE(c.rp_source.empty());
  EXPECT_FALSE(c.dimensions_source.empty());
  EXPECT_FALSE(c.inertial_source.empty());
  EXPECT_FALSE(c.gravity_compensated);
  EXPECT_EQ(c.j23_coupling, d.j23_coupling);
}

}  // namespace roprec::test
