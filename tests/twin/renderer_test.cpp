// Offscreen rendering (OSMesa): a frame of the standing twin is a valid PNG of the requested size,
// shows the robot (not a blank image), and changes when the robot moves.
#include "flexgait/twin/renderer.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "flexgait/twin/plant.hpp"

namespace flexgait::humanoid {
namespace {

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}

TEST(Renderer, DrawsTheTwinIntoAPng) {
  PlantParams p;
  HumanoidPlant plant(RobotParams{}, p);
  plant.reset(standing_pose(RobotParams{}, 0.75));
  Renderer renderer(plant, 320, 240);
  const std::vector<unsigned char> standing = renderer.render(plant);
  ASSERT_EQ(standing.size(), 320u * 240u * 3u);
  // The robot is in the middle of the picture: the centre column differs from the image corner.
  long differing = 0;
  for (int y = 0; y < 240; ++y)
    differing += std::memcmp(&standing[3 * (y * 320 + 160)], &standing[3 * (5 * 320 + 5)], 3) != 0;
  EXPECT_GT(differing, 100);
  const std::string png = encode_png(standing, 320, 240);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(be32(png, 16), 320u);
  EXPECT_EQ(be32(png, 20), 240u);
  EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND");
  // Another pose, another picture.
  JointVector bent = standing_pose(RobotParams{}, 0.70);
  plant.reset(bent);
  EXPECT_NE(renderer.render(plant), standing);
}

TEST(Renderer, DrawsAnArrowForAPush) {
  HumanoidPlant plant(RobotParams{}, PlantParams{});
  const JointVector pose = standing_pose(RobotParams{}, 0.75);
  plant.reset(pose);
  plant.set_push(Push{0.0, PushBody::kChest, {0, 200, 0}, 0.1});  // sideways: across the side view
  plant.step(pose);
  Renderer renderer(plant, 320, 240);
  const std::vector<unsigned char> pushed = renderer.render(plant);
  plant.reset(pose);
  plant.set_push(Push{});
  plant.step(pose);
  const std::vector<unsigned char> still = renderer.render(plant);
  // The orange arrow: pixels with much more red than blue appear only with the push.
  const auto orange = [](const std::vector<unsigned char>& rgb) {
    long n = 0;
    for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) n += rgb[i] > 150 && rgb[i + 2] < 80;
    return n;
  };
  EXPECT_GT(orange(pushed), 50 + orange(still));
}

}  // namespace
}  // namespace flexgait::humanoid
