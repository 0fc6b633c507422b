#pragma once
/// \file render_command.hpp
/// `flexgait render --run DIR`: a run's replay (DIR/replay.html) drawn offscreen with MuJoCo to
/// DIR/frames/frame_NNNNN.png and DIR/video.mp4 (ffmpeg); and the `--size WxH` option it shares
/// with `humanoid walk --render`.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <utility>

namespace flexgait::cli {

/// "WxH" → (W, H), each in 16 .. max [pixels]. Throws UsageError naming `option`, the text and what
/// is allowed.
std::pair<int, int> parse_render_size(const std::string& text, const std::string& option, int max_width,
                                      int max_height);

void add_render_command(CLI::App& app, std::function<int()>& action);

}  // namespace flexgait::cli
