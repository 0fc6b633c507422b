// The replay scene and its page: base64 against RFC 4648's test vectors; the JSON block round-
// trips the per-frame arrays bit for bit; frames start hidden (NaN); inconsistent sizes are
// refused; the page holds the block once, escaped so no "</" can end its script element early.
#include "flexgait/replay/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace flexgait::replay {
namespace {

template <class T>
std::vector<T> decode(const nlohmann::json& s) {
  const auto bytes = unbase64(s.get<std::string>());
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}

TEST(Base64, Rfc4648VectorsBothWays) {
  for (const auto& [in, out] : std::vector<std::pair<std::string, std::string>>{{"", ""},
                                                                                {"f", "Zg=="},
                                                                                {"fo", "Zm8="},
                                                                                {"foo", "Zm9v"},
                                                                                {"foob", "Zm9vYg=="},
                                                                                {"fooba", "Zm9vYmE="},
                                                                                {"foobar", "Zm9vYmFy"}}) {
    EXPECT_EQ(base64(in.data(), in.size()), out) << in;
    const auto back = unbase64(out);
    EXPECT_EQ(std::string(back.begin(), back.end()), in) << out;
  }
  EXPECT_THROW(unbase64("Zm9"), std::invalid_argument);   // not a multiple of 4
  EXPECT_THROW(unbase64("Zm=v"), std::invalid_argument);  // padding inside
  EXPECT_THROW(unbase64("Zm9*"), std::invalid_argument);  // outside the alphabet
}

Scene two_frames() {
  Scene s;
  s.title = "a </script> title";
  s.bodies.push_back({"ball", {Geom{}}});
  Layer arrows;
  arrows.name = "arrows";
  arrows.kind = LayerKind::Arrows;
  arrows.count = 2;
  arrows.palette = {{1, 0, 0, 1}, {0, 0, 1, 1}};
  s.layers.push_back(arrows);
  s.signals.push_back({"height", "m", {}, "body", "height and depth", "the ball's"});
  for (int f = 0; f < 2; ++f) {
    s.add_frame(0.1 * f + 1.0 / 3.0);
    s.set_pose(f, 0, {1.0 + f, 2, 3}, {1, 0, 0, 0});
    s.set_item(0, f, 1, {0, 0, 0}, {0, 0, 0.5 * f}, 1);
    s.set_signal(0, f, 3 + 0.25 * f);
  }
  return s;
}

TEST(ReplayJson, RoundTripsThePerFrameArrays) {
  const Scene s = two_frames();
  const auto j = nlohmann::json::parse(replay_json(s));
  EXPECT_EQ(j["format"], "flexgait-replay");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(decode<double>(j["time"]), s.time);  // float64: bit for bit
  EXPECT_EQ(decode<float>(j["poses"]), s.poses);
  const auto items = decode<float>(j["layers"][0]["data"]);
  ASSERT_EQ(items.size(), 2u * 2u * 6u);
  EXPECT_TRUE(std::isnan(items[0]));   // item 0 never set: hidden
  EXPECT_EQ(items[6 + 5], 0.0F);       // frame 0, item 1, b.z
  EXPECT_EQ(items[12 + 6 + 5], 0.5F);  // frame 1, item 1, b.z
  EXPECT_EQ(decode<unsigned char>(j["layers"][0]["color"]), (std::vector<unsigned char>{0, 1, 0, 1}));
  EXPECT_EQ(decode<float>(j["signals"][0]["data"]), (std::vector<float>{3.0F, 3.25F}));
  EXPECT_EQ(j["signals"][0]["panel"], "body");  // the page's tab, plot and legend line
  EXPECT_EQ(j["signals"][0]["plot"], "height and depth");
  EXPECT_EQ(j["signals"][0]["label"], "the ball's");
  EXPECT_EQ(j["title"], "a </script> title");            // the escape "<\/" reads back as "</"
  EXPECT_EQ(replay_json(s), replay_json(two_frames()));  // same scene, same bytes
}

TEST(Scene, AGrownLayerKeepsItsItemsAndHidesTheNewOnesInEarlierFrames) {
  Scene s = two_frames();
  const std::vector<float> before = s.layers[0].data;  // 2 frames × 2 items × 6 floats
  s.grow_layer(0, 3);
  s.check();
  ASSERT_EQ(s.layers[0].count, 3);
  for (int f = 0; f < 2; ++f)
    for (int i = 0; i < 12; ++i) {
      const float was = before[static_cast<std::size_t>(12 * f + i)];
      const float now = s.layers[0].data[static_cast<std::size_t>(18 * f + i)];
      EXPECT_TRUE(now == was || (std::isnan(now) && std::isnan(was))) << "frame " << f << ", float " << i;
      EXPECT_TRUE(std::isnan(s.layers[0].data[static_cast<std::size_t>(18 * f + 12 + i % 6)]));  // the new item
    }
  EXPECT_EQ(s.layers[0].color, (std::vector<std::uint8_t>{0, 1, 0, 0, 1, 0}));
  s.set_item(0, s.add_frame(2.0), 2, {1, 2, 3}, {4, 5, 6});
  s.check();
  EXPECT_EQ(s.layers[0].data.back(), 6.0F);
  s.grow_layer(0, 1);  // never shrinks
  EXPECT_EQ(s.layers[0].count, 3);
}

TEST(ReplayJson, RefusesInconsistentSizes) {
  Scene s = two_frames();
  s.poses.pop_back();
  EXPECT_THROW(replay_json(s), std::logic_error);
  s = two_frames();
  s.layers[0].color[0] = 2;  // outside its palette of two
  EXPECT_THROW(replay_json(s), std::logic_error);
  s = two_frames();
  s.signals.push_back({"depth", "mm", {0, 0}, "body", "height and depth", ""});  // one plot, one axis: one unit
  EXPECT_THROW(replay_json(s), std::logic_error);
  s.signals.back().unit = "m";
  EXPECT_NO_THROW(replay_json(s));
  s.signals.back().name = "height";  // the page finds a signal by its name
  EXPECT_THROW(replay_json(s), std::logic_error);
}

TEST(ReplayHtml, HoldsTheBlockOnceAndNoEarlyScriptEnd) {
  if (!replay_page_available()) GTEST_SKIP() << "built with FLEXGAIT_REPLAY=OFF";
  const std::string html = replay_html(two_frames());
  const std::string json = replay_json(two_frames());
  const std::size_t at = html.find(json);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(html.find(json, at + 1), std::string::npos);
  EXPECT_EQ(json.find("</"), std::string::npos);
  EXPECT_EQ(html.find("@FLEXGAIT_REPLAY_DATA@"), std::string::npos);
  // Offline: the page loads nothing from elsewhere (no script or stylesheet by address).
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("<link "), std::string::npos);
}

TEST(ReplayHtml, ReadsBackTheSceneItHolds) {
  if (!replay_page_available()) GTEST_SKIP() << "built with FLEXGAIT_REPLAY=OFF";
  const Scene s = two_frames();
  const Scene back = parse_replay_html(replay_html(s));
  EXPECT_EQ(back.title, s.title);
  EXPECT_EQ(back.time, s.time);
  EXPECT_EQ(replay_json(back), replay_json(s));  // every field, bit for bit
  EXPECT_THROW(parse_replay_html("<html></html>"), std::invalid_argument);
  std::string broken = replay_html(s);
  broken.replace(broken.find("\"poses\":\"") + 9, 4, "!!!!");
  EXPECT_THROW(parse_replay_html(broken), std::invalid_argument);
}

}  // namespace
}  // namespace flexgait::replay
