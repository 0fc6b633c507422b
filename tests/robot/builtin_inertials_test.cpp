// The builtin robot's bodies from THORMANG3's table (robot/builtin_inertials.hpp): the bodies weigh
// robot.total_mass together, the mass beyond the table goes half to the pelvis and half to the
// chest, lumping keeps every body physical, the legs weigh the same on both sides, and a total
// below the table's is refused.
#include "flexgait/robot/builtin_inertials.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "flexgait/robot/thormang3_inertials.hpp"
#include "inertia_checks.hpp"

namespace flexgait::humanoid {
namespace {

double total(const BuiltinInertials& b) {
  double m = b.pelvis.mass + b.chest.mass;
  for (const auto& side : b.leg)
    for (const BodyInertial& body : side) m += body.mass;
  return m;
}

TEST(BuiltinInertials, BodiesWeighTheTotalMassAndTheExtraIsSplitInTwo) {
  for (double total_mass : {thormang3_mass(), 57.0, 70.0}) {
    RobotParams r;
    r.total_mass = total_mass;
    const BuiltinInertials b = builtin_inertials(r);
    // A sum of 16 bodies of tens of kg: 1e-12 kg.
    EXPECT_NEAR(total(b), total_mass, 1e-12) << total_mass;
    const double extra = total_mass - thormang3_mass();
    EXPECT_NEAR(b.pelvis.mass, thormang3_link("pelvis").mass + 0.5 * extra, 1e-12);
    for (int i = 0; i < 7; ++i)
      EXPECT_EQ(b.leg[0][static_cast<std::size_t>(i)].mass, b.leg[1][static_cast<std::size_t>(i)].mass) << i;
    EXPECT_EQ(b.leg[0][6].mass, thormang3_link("l_leg_foot").mass);
  }
}

TEST(BuiltinInertials, EveryBodyIsPhysical) {
  const BuiltinInertials b = builtin_inertials(RobotParams{});
  testing::expect_physical_inertial("pelvis", b.pelvis.mass, b.pelvis.inertia);
  testing::expect_physical_inertial("chest", b.chest.mass, b.chest.inertia);
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < 7; ++i) {
      const BodyInertial& body = b.leg[static_cast<std::size_t>(s)][static_cast<std::size_t>(i)];
      testing::expect_physical_inertial("leg " + std::to_string(s) + "." + std::to_string(i), body.mass, body.inertia);
    }
  // The chest lumps torso, head and arms spread over a metre: about its centre it is far more
  // than the torso alone (parallel axes only add).
  const double torso_trace = thormang3_link("torso_y").inertia[0] + thormang3_link("torso_y").inertia[3] +
                             thormang3_link("torso_y").inertia[5];
  EXPECT_GT(b.chest.inertia[0] + b.chest.inertia[3] + b.chest.inertia[5], torso_trace);
}

TEST(BuiltinInertials, ATotalBelowTheTableIsRefused) {
  RobotParams r;
  r.total_mass = thormang3_mass() - 0.01;
  EXPECT_THROW(builtin_inertials(r), std::invalid_argument);
}

}  // namespace
}  // namespace flexgait::humanoid
