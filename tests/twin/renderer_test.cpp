// Offscreen rendering (OSMesa): a frame of the standing twin is a valid PNG of the requested size,
// shows the robot (not a blank image), and changes when the robot moves; a 10 N push shows its
// arrow; the side camera frames the walk's stretch (the robot left of the middle at the start of a
// walk ahead, right of it at the end); a replay scene's frame shows its bodies and markers.
#include "flexgait/twin/renderer.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "flexgait/core/config.hpp"
#include "flexgait/twin/plant.hpp"

namespace flexgait::twin {
namespace {

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}

/// Pixels with much more red than blue: the push arrow's orange (the sky is blue, the floor grey).
long orange(const std::vector<unsigned char>& rgb) {
  long n = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) n += rgb[i] > 150 && rgb[i + 2] < 80;
  return n;
}

TEST(Renderer, DrawsTheTwinIntoAPng) {
  PlantParams p;
  HumanoidPlant plant(humanoid::RobotParams{}, p);
  plant.reset(standing_pose(humanoid::RobotParams{}, 0.75));
  Renderer renderer(plant, RenderView{320, 240, CameraView::kFollow});
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
  humanoid::JointVector bent = standing_pose(humanoid::RobotParams{}, 0.70);
  plant.reset(bent);
  EXPECT_NE(renderer.render(plant), standing);
}

TEST(Renderer, DrawsAnArrowForATenNewtonPush) {
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  const humanoid::JointVector pose = standing_pose(humanoid::RobotParams{}, 0.75);
  plant.reset(pose);
  plant.set_push(Push{0.0, PushBody::kChest, {10, 0, 0}, 0.1});  // forward: across the side view
  plant.step(pose);
  Renderer renderer(plant, RenderView{640, 360, CameraView::kSide, 0, 0});
  const std::vector<unsigned char> pushed = renderer.render(plant);
  plant.reset(pose);
  plant.set_push(Push{});
  plant.step(pose);
  const std::vector<unsigned char> still = renderer.render(plant);
  // The arrow is 0.16 m long and 0.03 m wide, 3 m away: ~35 × 6 pixels at 640 × 360 (half of the
  // 1280 × 720 default), most of them orange under the light.
  EXPECT_GT(orange(pushed), 60 + orange(still));
}

/// The mean column of the robot's pixels in the band of rows between its head and the horizon,
/// where the rest is sky (blue above red).
double robot_column(const std::vector<unsigned char>& rgb, int width, int height) {
  double sum = 0;
  long n = 0;
  for (int y = height * 15 / 100; y < height * 26 / 100; ++y)
    for (int x = 0; x < width; ++x) {
      const unsigned char* p = &rgb[3 * (static_cast<std::size_t>(y) * width + x)];
      if (p[2] > p[0] + 25) continue;  // sky
      sum += x;
      ++n;
    }
  return n > 20 ? sum / static_cast<double>(n) : -1;
}

TEST(Renderer, SideCameraFramesTheWalk) {
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  plant.reset(standing_pose(humanoid::RobotParams{}, 0.75));
  // The robot at x = 0: the start of a 2 m walk ahead is left of the middle, its end right of it.
  Renderer start(plant, RenderView{480, 270, CameraView::kSide, 0, 2});
  const double at_start = robot_column(start.render(plant), 480, 270);
  Renderer end(plant, RenderView{480, 270, CameraView::kSide, -2, 0});
  const double at_end = robot_column(end.render(plant), 480, 270);
  ASSERT_GT(at_start, 0);
  ASSERT_GT(at_end, 0);
  EXPECT_LT(at_start, 240 - 60);
  EXPECT_GT(at_end, 240 + 60);
}

TEST(Renderer, RefusesSizesOutsideTheBuffer) {
  HumanoidPlant plant(humanoid::RobotParams{}, PlantParams{});
  EXPECT_THROW(Renderer(plant, RenderView{0, 0}), UsageError);
  EXPECT_THROW(Renderer(plant, RenderView{1920, 1080}), UsageError);  // the twin's buffer is 1280 × 720
  EXPECT_EQ(camera_view("front"), CameraView::kFront);
  EXPECT_FALSE(camera_view("top"));
}

TEST(SceneRenderer, DrawsBodiesAndMarkersOfAFrame) {
  replay::Scene s;
  s.camera = {{0, 0, 0.5}, 3, -90, 10, ""};
  replay::Geom floor;
  floor.type = replay::GeomType::Plane;
  floor.size = {5, 5, 0};
  floor.checker = true;
  s.statics.push_back(floor);
  replay::Geom ball;
  ball.type = replay::GeomType::Sphere;
  ball.size = {0.2, 0, 0};
  ball.rgba = {0.1F, 0.2F, 0.9F, 1};
  s.bodies.push_back({"ball", {ball}});
  replay::Layer dots;
  dots.name = "dots";
  dots.kind = replay::LayerKind::Points;
  dots.count = 1;
  dots.width = 0.1;
  dots.palette = {{1, 0.5F, 0, 1}};
  s.layers.push_back(dots);
  for (int f = 0; f < 2; ++f) {
    s.add_frame(f);
    s.set_pose(f, 0, {-0.6 + 1.2 * f, 0, 0.5}, {1, 0, 0, 0});
    s.set_item(0, f, 0, {0.6 - 1.2 * f, 0, 0.5}, {0, 0, 0});
  }
  SceneRenderer r(320, 180);
  const std::vector<unsigned char> first = r.render(s, 0);
  const std::vector<unsigned char> second = r.render(s, 1);
  // The ball (blue) and the dot (orange) swap sides: the left half's orange pixels move right.
  auto count = [](const std::vector<unsigned char>& rgb, bool left, bool want_orange) {
    long n = 0;
    for (int y = 0; y < 180; ++y)
      for (int x = left ? 0 : 160; x < (left ? 160 : 320); ++x) {
        const unsigned char* p = &rgb[3 * (static_cast<std::size_t>(y) * 320 + x)];
        n += want_orange ? (p[0] > 150 && p[2] < 80) : (p[2] > 120 && p[0] < 60);
      }
    return n;
  };
  EXPECT_GT(count(first, false, true), 100);  // the dot at x = +0.6: the right half
  EXPECT_LT(count(first, true, true), 10);
  EXPECT_GT(count(second, true, true), 100);
  EXPECT_GT(count(first, true, false), 100);  // the ball at x = −0.6: the left half
  EXPECT_GT(count(second, false, false), 100);
  EXPECT_THROW(SceneRenderer(0, 10), UsageError);
}

}  // namespace
}  // namespace flexgait::twin
