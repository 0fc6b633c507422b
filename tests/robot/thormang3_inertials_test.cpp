// THORMANG3's CAD table (robot/thormang3_inertials.hpp) is data; its test is one of consistency:
// every link a physical rigid body, left and right links of equal mass, the table's sum 42.533 kg
// (spec humanoid.md, "The robot"), and an unknown link refused.
#include "flexgait/robot/thormang3_inertials.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "inertia_checks.hpp"

namespace flexgait::humanoid {
namespace {

// The table's 36 rows, by name (thormang3-inertials.csv).
constexpr const char* kSides[] = {"arm_sh_p1", "arm_sh_r", "arm_sh_p2",  "arm_el_y",  "arm_wr_r",  "arm_wr_y",
                                  "arm_wr_p",  "arm_grip", "arm_grip_1", "leg_hip_y", "leg_hip_r", "leg_hip_p",
                                  "leg_kn_p",  "leg_an_p", "leg_an_r",   "leg_foot"};
constexpr const char* kMiddle[] = {"pelvis", "torso_y", "head_y", "head_p"};

TEST(Thormang3Inertials, EveryLinkIsAPhysicalBodyAndTheSidesWeighTheSame) {
  double sum = 0;
  for (const char* m : kMiddle) {
    const Thormang3Link& l = thormang3_link(m);
    EXPECT_EQ(l.name, m);
    testing::expect_physical_inertial(m, l.mass, l.inertia);
    sum += l.mass;
  }
  for (const char* s : kSides) {
    const Thormang3Link& left = thormang3_link(std::string("l_") + s);
    const Thormang3Link& right = thormang3_link(std::string("r_") + s);
    testing::expect_physical_inertial(std::string("l_") + s, left.mass, left.inertia);
    testing::expect_physical_inertial(std::string("r_") + s, right.mass, right.inertia);
    EXPECT_EQ(left.mass, right.mass) << s;
    sum += left.mass + right.mass;
  }
  // These 36 rows are the whole table: their sum is thormang3_mass(), to rounding (1e-12 kg).
  // The spec's "42.533 kg" is the sum 42.53350 cut to 3 decimals.
  EXPECT_NEAR(sum, thormang3_mass(), 1e-12);
  EXPECT_GE(thormang3_mass(), 42.533);
  EXPECT_LT(thormang3_mass(), 42.534);
}

TEST(Thormang3Inertials, UnknownLinkIsALogicError) {
  EXPECT_THROW(thormang3_link("l_leg_tail"), std::logic_error);
}

}  // namespace
}  // namespace flexgait::humanoid
