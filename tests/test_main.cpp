// The main of every GoogleTest program: GoogleTest's own, after trapping floating-point
// exceptions when the build asks (tests/floating_point_traps.hpp).
#include <gtest/gtest.h>

#include "floating_point_traps.hpp"

int main(int argc, char** argv) {
  hsr::test::trapFloatingPointWhenAsked();
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
