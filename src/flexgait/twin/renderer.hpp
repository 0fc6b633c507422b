#pragma once
/// \file renderer.hpp
/// Offscreen pictures of the twin: MuJoCo's renderer in an OSMesa (software OpenGL) context, so no
/// display is needed, and PNG files (zlib). The camera follows the pelvis. For evaluation and
/// presentation only; nothing here feeds a controller.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "flexgait/twin/plant.hpp"

namespace flexgait::humanoid {

class Renderer {
 public:
  /// Draws `plant`'s twin (or any copy's: they share the model; its visual/global offwidth and
  /// offheight bound the size). Throws std::runtime_error when no OSMesa context can be made.
  Renderer(const HumanoidPlant& plant, int width, int height);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Draws the plant's present state seen from the side, looking at the pelvis, with an arrow for
  /// each body's applied force (a push); returns RGB rows top to bottom (width × height × 3 bytes).
  const std::vector<unsigned char>& render(const HumanoidPlant& plant);
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
  int width_, height_;
  std::vector<unsigned char> rgb_, flipped_;
};

/// Encodes RGB rows (top to bottom) as PNG bytes.
std::string encode_png(const std::vector<unsigned char>& rgb, int width, int height);

/// Makes DIR/video.mp4 from DIR/frames/frame_%05d.png with ffmpeg, if ffmpeg is on the PATH.
/// Returns false (and leaves the frames) when it is not there or fails.
bool encode_video(const std::filesystem::path& dir, double frame_rate);

}  // namespace flexgait::humanoid
