#include "render_command.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "flexgait/core/atomic_file.hpp"
#include "flexgait/core/config.hpp"
#include "flexgait/core/progress.hpp"
#include "flexgait/core/text.hpp"
#include "flexgait/replay/scene.hpp"
#include "flexgait/twin/renderer.hpp"
#include "options.hpp"

namespace flexgait::cli {

std::pair<int, int> parse_render_size(const std::string& text, const std::string& option, int max_width,
                                      int max_height) {
  const std::size_t x = text.find('x');
  int w = 0, h = 0;
  const char* end = text.data() + text.size();
  const bool ok = x != std::string::npos && x > 0 &&
                  std::from_chars(text.data(), text.data() + x, w).ptr == text.data() + x &&
                  std::from_chars(text.data() + x + 1, end, h).ptr == end && x + 1 < text.size();
  if (!ok || w < 16 || h < 16 || w > max_width || h > max_height)
    throw UsageError(fmt::format("{} '{}': expected WIDTHxHEIGHT in pixels, from 16x16 to {}x{}", option,
                                 one_line(text, 100), max_width, max_height));
  return {w, h};
}

namespace {

struct RenderArgs {
  std::string run;  ///< --run DIR
  std::string size = "1280x720";
  double fps = 30;  ///< [1/s] of simulated time
};

int render(const RenderArgs& a) {
  const auto [width, height] = parse_render_size(a.size, "--size", 4096, 4096);
  const std::filesystem::path dir(a.run);
  const std::filesystem::path page = dir / "replay.html";
  std::error_code error;
  if (!std::filesystem::is_regular_file(page, error))
    throw UsageError(fmt::format(
        "--run '{}': no replay.html in it (rimless simulate writes one into its run directory)", one_line(a.run, 300)));
  std::ifstream in(page, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  replay::Scene scene;
  try {
    scene = replay::parse_replay_html(text.str());
  } catch (const std::invalid_argument& e) {
    throw UsageError(fmt::format("--run '{}': replay.html cannot be read: {}", one_line(a.run, 300), e.what()));
  }
  if (scene.frames() == 0) throw UsageError(fmt::format("--run '{}': replay.html has no frames", one_line(a.run, 300)));
  check_output_directory(dir / "frames", "--run");
  std::filesystem::create_directories(dir / "frames");
  for (const auto& entry : std::filesystem::directory_iterator(dir / "frames"))  // a longer earlier render's frames
    if (entry.path().extension() == ".png") std::filesystem::remove(entry.path());
  twin::SceneRenderer renderer(width, height);
  ProgressBar bar(scene.time.back() - scene.time.front(), "s drawn");
  int written = 0;
  double next = scene.time.front();
  for (int f = 0; f < scene.frames(); ++f) {
    if (scene.time[static_cast<std::size_t>(f)] < next && f + 1 < scene.frames()) continue;
    next += 1.0 / a.fps;
    const auto& rgb = renderer.render(scene, f);
    write_file_atomic(dir / "frames" / fmt::format("frame_{:05d}.png", written++),
                      twin::encode_png(rgb, width, height));
    bar.show(scene.time[static_cast<std::size_t>(f)] - scene.time.front());
  }
  const bool video = twin::encode_video(dir, a.fps);
  fmt::print("{} frames of {}x{} in {}{}\n", written, width, height, (dir / "frames").string(),
             video ? fmt::format(", {}", (dir / "video.mp4").string()) : " (no ffmpeg: no video.mp4)");
  return 0;
}

}  // namespace

void add_render_command(CLI::App& app, std::function<int()>& action) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* r = app.add_subcommand(
      "render",
      "Draw a run's replay (RUN/replay.html, e.g. the rimless wheel's) offscreen with MuJoCo: PNG frames in "
      "RUN/frames and RUN/video.mp4 (ffmpeg)");
  r->add_option("--run", args->run, "run directory holding replay.html")->required();
  r->add_option("--size", args->size, "frame size WIDTHxHEIGHT in pixels")->capture_default_str();
  r->add_option("--fps", args->fps, "frames per second of simulated time (1/s)")
      ->check(finite_number() & CLI::Range(1.0, 250.0))
      ->capture_default_str();
  r->callback([args, &action] { action = [args] { return render(*args); }; });
}

}  // namespace flexgait::cli
