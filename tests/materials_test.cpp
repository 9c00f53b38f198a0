#include "compensator/process/materials.hpp"

#include <gtest/gtest.h>

#include "compensator/support/rotation.hpp"

namespace roprec {
namespace {

TEST(Materials, RequiredAlloysWithIscarGroupValues) {
  struct Expect {
    const char* query;
    const char* name;
    double kc11_N_mm2;
    const char* group;
  };
  // ISCAR material-group table (docs/process.md §2.3): group 22 800/0.25, 23 and 24 700/0.25.
  const Expect e[] = {{"Al 6061-T6", "Al 6061-T6", 800, "ISCAR 22"},
                      {"6061-t6", "Al 6061-T6", 800, "ISCAR 22"},
                      {"AL7075-T6", "Al 7075-T6", 800, "ISCAR 22"},
                      {"AlSi7Mg", "AlSi7Mg (A356-T6)", 700, "ISCAR 24"},
                      {"A356", "AlSi7Mg (A356-T6)", 700, "ISCAR 24"},
                      {"AlSi9Cu3", "AlSi9Cu3", 700, "ISCAR 23"},
                      {"EN AC-46000", "AlSi9Cu3", 700, "ISCAR 23"}};
  for (const Expect& x : e) {
    const Material* m = findMaterial(x.query);
    ASSERT_NE(m, nullptr) << x.query;
    EXPECT_EQ(m->name, x.name);
    EXPECT_EQ(m->group, x.group);
    EXPECT_DOUBLE_EQ(m->kc11, x.kc11_N_mm2 * 1e6);
    EXPECT_DOUBLE_EQ(m->mc, 0.25);
    EXPECT_DOUBLE_EQ(m->milling.kc11, m->kc11);
    EXPECT_DOUBLE_EQ(m->drilling.tangential.k0, m->kc11);
    EXPECT_DOUBLE_EQ(m->drilling.tangential.m, 0.25);
  }
}

TEST(Materials, EveryCoefficientCarriesASource) {
  for (const Material& m : materialTable()) {
    EXPECT_FALSE(m.kienzle_source.empty()) << m.name;
    EXPECT_FALSE(m.drilling_source.empty()) << m.name;
    EXPECT_FALSE(m.chisel_source.empty()) << m.name;
    EXPECT_FALSE(m.milling_ratio_source.empty()) << m.name;
    // §2.3 illustrative calibration: bt −0.010/°, ba −0.0185/°, aa 0.80; chisel ratio 1.2.
    EXPECT_NEAR(m.drilling.tangential.b * kDeg, -0.010, 1e-15);
    EXPECT_NEAR(m.drilling.axial.b * kDeg, -0.0185, 1e-15);
    EXPECT_DOUBLE_EQ(m.drilling.axial.a, 0.80);
    EXPECT_DOUBLE_EQ(m.drilling.chisel.thrust_ratio, 1.2);
  }
}

TEST(Materials, UnknownMaterialIsNotGuessed) {
  EXPECT_EQ(findMaterial("Ti6Al4V"), nullptr);
  EXPECT_EQ(findMaterial(""), nullptr);
  EXPECT_NE(materialNames().find("AlSi9Cu3"), std::string::npos);
}

}  // namespace
}  // namespace roprec
