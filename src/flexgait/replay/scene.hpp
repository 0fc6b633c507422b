#pragma once
/// \file scene.hpp
/// A run as a scene to replay (docs/guide/replay.md): rigid bodies made of primitive shapes with
/// a pose per frame, marker layers (segments, springs, arrows, points) with their ends per frame,
/// and signals with a value per frame. The same scene feeds the interactive page (replay_html)
/// whichever model made it: the rimless wheel (rimless/replay.hpp) and the humanoid twin
/// (twin/replay_recorder.hpp).
///
/// Conventions are MuJoCo's: world frame z up [m], quaternions (w, x, y, z), a geom's size in
/// half-lengths (sphere: radius; capsule and cylinder: radius, half-length along local z; box:
/// half-sizes; plane: half-sizes in x and y, 0 = unbounded). Per-frame values are float32 (7
/// significant digits: 2 µm at 20 m), which keeps a 10-step walk's page near 1 MB.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace flexgait::replay {

enum class GeomType { Plane, Sphere, Capsule, Ellipsoid, Cylinder, Box, Mesh };
/// "plane", "sphere", ... (the page's names).
const char* geom_type_name(GeomType type);

struct Geom {
  GeomType type = GeomType::Sphere;
  std::array<double, 3> size{0.05, 0.05, 0.05};  ///< half-lengths as above [m]
  std::array<double, 3> pos{0, 0, 0};            ///< in the body's frame (statics: the world's) [m]
  std::array<double, 4> quat{1, 0, 0, 0};        ///< (w, x, y, z), body frame
  std::array<float, 4> rgba{0.7F, 0.7F, 0.7F, 1.0F};
  bool checker = false;              ///< plane only: 1 m checker squares with a grid line every 2 m
  std::vector<float> vertices;       ///< Mesh only: (nvert × 3) [m], in the geom's frame
  std::vector<std::uint32_t> faces;  ///< Mesh only: (nface × 3) vertex indices
};

/// A rigid body: its geoms move with its pose.
struct Body {
  std::string name;
  std::vector<Geom> geoms;
};

/// What a layer draws per item: a segment or spring from a to b, an arrow from a to b, a point at a.
enum class LayerKind { Segments, Springs, Arrows, Points };
const char* layer_kind_name(LayerKind kind);
/// Floats per item and frame: 3 for points (x, y, z), 6 for the others (a, b).
int layer_item_floats(LayerKind kind);

/// Markers shown or hidden together (a toggle on the page). An item whose first coordinate is
/// NaN is hidden in that frame.
struct Layer {
  std::string name;
  LayerKind kind = LayerKind::Segments;
  int count = 0;        ///< items per frame
  double width = 0.02;  ///< segment/point radius, spring coil radius [m]
  int turns = 10;       ///< Springs only: coil turns
  std::vector<std::array<float, 4>> palette{{1.0F, 0.5F, 0.0F, 1.0F}};  ///< the items' colours
  std::vector<std::string> legend;                                      ///< a name per palette colour (optional)
  bool visible = true;                                                  ///< shown when the page opens
  std::vector<float> data;                                              ///< (frames × count × layer_item_floats)
  std::vector<std::uint8_t> color;                                      ///< (frames × count) palette indices
};

/// A value per frame, plotted on the page below the scene. Signals are grouped: a panel (one of the
/// page's tabs) holds plots, a plot holds the lines of its signals on shared axes (so they share
/// one unit), each named in the plot's legend.
struct Signal {
  std::string name;         ///< its key, unique in the scene (e.g. the log's column)
  std::string unit;         ///< e.g. "m", "N m" ("": none)
  std::vector<float> data;  ///< (frames)
  std::string panel;        ///< the panel that shows it ("": "signals")
  std::string plot;         ///< its plot in the panel, titled so ("": a plot of its own, titled `name`)
  std::string label;        ///< its line's name in the plot's legend ("": `name`)
};

/// Where the page's camera starts: looking at `target` from `distance` at `azimuth` (degrees
/// about z from +x) and `elevation` (degrees above the horizontal); it follows body `follow`'s
/// horizontal motion while the page's "follow" box is ticked ("" = fixed).
struct Camera {
  std::array<double, 3> target{0, 0, 0.5};
  double distance = 4, azimuth = -90, elevation = 10;
  std::string follow;
};

struct Scene {
  std::string title;
  Camera camera;
  double shadow_extent = 6;  ///< half-width of the region that casts shadows [m]
  std::vector<Geom> statics;
  std::vector<Body> bodies;
  std::vector<Layer> layers;
  std::vector<Signal> signals;
  std::vector<double> time;  ///< (frames) [s]; written as float64 (a frame's time is its log row's)
  std::vector<float> poses;  ///< (frames × bodies × 7): position (3), quaternion (w, x, y, z)

  int frames() const { return static_cast<int>(time.size()); }
  /// Appends a frame at time t [s]: poses, layer items and signals NaN (hidden) until set.
  /// Bodies, layers and signals must all be added before the first frame. Returns its index.
  int add_frame(double t);
  void set_pose(int frame, int body, const std::array<double, 3>& pos, const std::array<double, 4>& quat);
  /// Item k of layer `layer` in `frame`: a (and b) [m], palette index `color`.
  void set_item(int layer, int frame, int k, const std::array<double, 3>& a, const std::array<double, 3>& b,
                int color = 0);
  void set_signal(int signal, int frame, double value);
  /// Makes layer `layer` hold `count` items per frame (at least its count now): the frames so far
  /// keep their items, the new items are hidden (NaN) in them.
  void grow_layer(int layer, int count);
  /// Keeps frames 0, 2, 4, ... (halves the frame rate: a recorder's bound on memory).
  void drop_odd_frames();
  /// Throws std::logic_error if an array's size disagrees with the frames, bodies and layers.
  void check() const;
};

/// The scene's JSON block (format "flexgait-replay", version 1): per-frame arrays as base64 of
/// little-endian float32 (time: float64); deterministic bytes for a given scene.
std::string replay_json(const Scene& scene);

/// Whether this build holds the page (built from web/ with three.js; FLEXGAIT_REPLAY=ON).
bool replay_page_available();

/// The self-contained page: the bundled viewer with `scene`'s JSON block inside. Throws
/// std::runtime_error if !replay_page_available().
std::string replay_html(const Scene& scene);

/// The scene in a page that replay_html wrote (its JSON block read back), e.g. to draw a run's
/// replay offscreen. Throws std::invalid_argument saying what is missing or malformed.
Scene parse_replay_html(std::string_view html);

/// Standard base64 (RFC 4648, with padding) of `size` bytes, and back (std::invalid_argument for
/// a character outside the alphabet or a length that is not a multiple of 4).
std::string base64(const void* bytes, std::size_t size);
std::vector<unsigned char> unbase64(std::string_view text);

}  // namespace flexgait::replay
