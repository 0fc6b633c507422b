#pragma once
/// \file renderer.hpp
/// Offscreen pictures: MuJoCo's renderer in an OSMesa (software OpenGL) context, so no display is
/// needed, and PNG files (zlib). Two subjects: the twin (Renderer, from the plant's model and
/// state) and any replay scene (SceneRenderer, replay/scene.hpp: the rimless wheel, or a recorded
/// walk), both with the same look: a sky gradient, a checkered floor with a 1 m grid, a light that
/// casts shadows. For evaluation and presentation only; nothing here feeds a controller.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flexgait/replay/scene.hpp"
#include "flexgait/twin/plant.hpp"

namespace flexgait::twin {

/// Where the twin's camera looks from.
enum class CameraView {
  kSide,    ///< fixed, from the robot's left, framing the whole walk (RenderView::walk_from/walk_to)
  kFollow,  ///< follows the pelvis from behind and to the left (the former default)
  kFront,   ///< follows the pelvis from ahead of it
};
/// "side", "follow", "front"; std::nullopt for another word.
std::optional<CameraView> camera_view(std::string_view name);

struct RenderView {
  int width = 1280, height = 720;  ///< [pixels], at most the model's offscreen buffer (1280 × 720)
  CameraView camera = CameraView::kSide;
  /// kSide: the stretch of x [m] the walk covers (e.g. the plan's first and last footprints); the
  /// camera looks at its middle from far enough to see all of it with a margin.
  double walk_from = 0, walk_to = 1;
};

/// A sole's rectangle on the floor.
struct FootprintMarker {
  std::array<double, 3> centre{};                 ///< [m]
  double yaw = 0;                                 ///< [rad]
  double half_length = 0.11, half_width = 0.065;  ///< [m]
};

/// What the controller knows and the twin does not, drawn when given (one plain record per frame,
/// filled by the walk's loop, experiments/walk_markers.hpp): planned and actual footprints, the
/// ZMP (true, of the contact forces) and the controller's reference ZMP, the centre of mass's
/// ground projection, the capture point, and lines of text (time, step, compensation mode).
/// Colours (kMarkerColours): planned footprints blue, actual green, ZMP red, reference ZMP yellow,
/// COM black, capture point magenta; each point a disc on the floor under a ball (seen from the side).
struct RenderMarkers {
  std::vector<FootprintMarker> planned, actual;
  std::optional<std::array<double, 3>> zmp, zmp_ref, com_ground, capture_point;  ///< [m], world
  std::string overlay;  ///< drawn at the top left; lines separated by '\n'
};

/// The markers' colours (RGBA), in RenderMarkers' order: planned and actual footprints, ZMP,
/// reference ZMP, COM ground projection, capture point.
enum MarkerColour { kPlannedColour, kActualColour, kZmpColour, kZmpRefColour, kComColour, kCaptureColour };
inline constexpr std::array<std::array<float, 4>, 6> kMarkerColours{{{0.2F, 0.45F, 0.95F, 0.45F},
                                                                     {0.15F, 0.7F, 0.25F, 0.8F},
                                                                     {0.9F, 0.1F, 0.1F, 1},
                                                                     {0.95F, 0.8F, 0.05F, 1},
                                                                     {0.1F, 0.1F, 0.1F, 1},
                                                                     {0.8F, 0.2F, 0.8F, 1}}};

/// A push drawn as an arrow: along the force, ending kPushGap [m] before the pushed body's centre
/// of mass (outside the torso), 0.1 m + kPushScale per newton long, at most 1 m (a 10 N push:
/// 0.16 m, ~60 pixels at 1280 × 720 from the side camera).
inline constexpr double kPushGap = 0.3;      ///< [m]
inline constexpr double kPushScale = 0.006;  ///< [m/N]
struct PushArrow {
  std::array<double, 3> from{}, to{};  ///< [m], world
  double newtons = 0;                  ///< |F| [N]
};
/// The arrow of the push acting on the plant now (xfrc_applied of its first pushed body); none
/// when no body is pushed.
std::optional<PushArrow> push_arrow(const HumanoidPlant& plant);

class Renderer {
 public:
  /// Draws `plant`'s twin (or any copy's: they share the model; its visual/global offwidth and
  /// offheight bound the size). Throws UsageError for a size outside 1 .. the buffer and
  /// std::runtime_error when no OSMesa context can be made.
  Renderer(const HumanoidPlant& plant, const RenderView& view);
  /// A camera that follows the pelvis (kFollow), for callers that do not know the walk's stretch.
  Renderer(const HumanoidPlant& plant, int width, int height)
      : Renderer(plant, RenderView{width, height, CameraView::kFollow}) {}
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Draws the plant's present state from the view's camera, with `markers` and the push's arrow
  /// (push_arrow) with the force written beside it. Returns RGB rows top to bottom (width × height
  /// × 3 bytes).
  const std::vector<unsigned char>& render(const HumanoidPlant& plant, const RenderMarkers& markers = {});
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
  RenderView view_;
  int width_, height_;
  std::vector<unsigned char> rgb_;
};

/// Draws frames of a replay scene (its statics, bodies and marker layers; its camera, following
/// its `follow` body), with the time written at the top left.
class SceneRenderer {
 public:
  /// Throws UsageError for a size outside 1 .. 4096 and std::runtime_error when no OSMesa context
  /// can be made.
  SceneRenderer(int width, int height);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// RGB rows top to bottom (width × height × 3 bytes) of `frame` of `scene`.
  const std::vector<unsigned char>& render(const replay::Scene& scene, int frame);

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
  int width_, height_;
  std::vector<unsigned char> rgb_;
};

/// Encodes RGB rows (top to bottom) as PNG bytes.
std::string encode_png(const std::vector<unsigned char>& rgb, int width, int height);

/// Makes DIR/video.mp4 from DIR/frames/frame_%05d.png with ffmpeg, if ffmpeg is on the PATH.
/// Returns false (and leaves the frames) when it is not there or fails.
bool encode_video(const std::filesystem::path& dir, double frame_rate);

}  // namespace flexgait::twin
