// The witness hsr why's histories are kept in (renderer/steps/why.hpp): only the pixels
// asked about have a history, each pixel its own, returned in the order they were asked.
#include <gtest/gtest.h>

#include "renderer/steps/why.hpp"

namespace hsr {
namespace {

TEST(PixelWitness, OnlyThePixelsAskedAboutHaveAHistoryEachItsOwnInTheOrderAsked) {
  PixelWitness witness({{5, 2}, {0, 0}, {3, 7}}, 10);
  ASSERT_EQ(witness.count(), 3u);
  EXPECT_EQ(witness.at(2, 5), nullptr);  // x and y swapped
  EXPECT_EQ(witness.at(9, 9), nullptr);
  EXPECT_EQ(witness.at(5, 3), nullptr);
  ASSERT_NE(witness.at(0, 0), nullptr);
  witness.at(5, 2)->push_back({1, "written", "", 2.0, true, {}});
  witness.at(3, 7)->push_back({2, "written", "", 1.0, true, {}});
  witness.at(3, 7)->push_back({3, "lost the depth test", "", 4.0, false, {}});
  EXPECT_EQ(witness.pixel(0).x, 5);
  EXPECT_EQ(witness.pixel(2).y, 7);
  ASSERT_EQ(witness.history(0).size(), 1u);
  EXPECT_EQ(witness.history(0)[0].id, 1u);
  EXPECT_TRUE(witness.history(1).empty());
  ASSERT_EQ(witness.history(2).size(), 2u);
  EXPECT_EQ(witness.history(2)[1].outcome, "lost the depth test");
  EXPECT_EQ(witness.events(), 3);
}

}  // namespace
}  // namespace hsr
