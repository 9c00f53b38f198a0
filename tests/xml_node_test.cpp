// The XML helpers (compensator/support/xml_node.hpp): the "did you mean" hint for an unknown name.
#include "compensator/support/xml_node.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace roprec {
namespace {

TEST(XmlNames, DidYouMeanFindsNearMissesOnly) {
  const std::vector<std::string> known = {"mass_kg", "com_mm", "name", "diameter"};
  EXPECT_EQ(didYouMean("mas_kg", known), " (did you mean 'mass_kg'?)");
  EXPECT_EQ(didYouMean("MASS_KG", known), " (did you mean 'mass_kg'?)");
  EXPECT_EQ(didYouMean("dia", known), " (did you mean 'diameter'?)");
  EXPECT_EQ(didYouMean("colour", known), "");
  EXPECT_EQ(didYouMean("tolerence", {"tolerance"}, "<", ">"), " (did you mean <tolerance>?)");
}

}  // namespace
}  // namespace roprec
