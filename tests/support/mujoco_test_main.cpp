// main() of every test program that runs MuJoCo (tests/CMakeLists.txt, flexgait_test): GoogleTest
// with the MuJoCo warning check (mujoco_warnings.hpp).
#include <gtest/gtest.h>

#include "mujoco_warnings.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  flexgait::test_support::install_mujoco_warning_check();
  return RUN_ALL_TESTS();
}
