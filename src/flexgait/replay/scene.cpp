#include "flexgait/replay/scene.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>

namespace flexgait::replay {

static_assert(std::endian::native == std::endian::little, "the page reads little-endian float32 arrays");

namespace detail {
extern const unsigned char kReplayTemplate[];
extern const std::size_t kReplayTemplateSize;
}  // namespace detail

const char* geom_type_name(GeomType type) {
  switch (type) {
    case GeomType::Plane:
      return "plane";
    case GeomType::Sphere:
      return "sphere";
    case GeomType::Capsule:
      return "capsule";
    case GeomType::Ellipsoid:
      return "ellipsoid";
    case GeomType::Cylinder:
      return "cylinder";
    case GeomType::Box:
      return "box";
    case GeomType::Mesh:
      return "mesh";
  }
  return "sphere";
}

const char* layer_kind_name(LayerKind kind) {
  switch (kind) {
    case LayerKind::Segments:
      return "segments";
    case LayerKind::Springs:
      return "springs";
    case LayerKind::Arrows:
      return "arrows";
    case LayerKind::Points:
      return "points";
  }
  return "segments";
}

int layer_item_floats(LayerKind kind) {
  return kind == LayerKind::Points ? 3 : 6;
}

int Scene::add_frame(double t) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  time.push_back(t);
  poses.resize(poses.size() + bodies.size() * 7, kNaN);
  for (Layer& l : layers) {
    l.data.resize(l.data.size() + static_cast<std::size_t>(l.count * layer_item_floats(l.kind)), kNaN);
    l.color.resize(l.color.size() + static_cast<std::size_t>(l.count), 0);
  }
  for (Signal& s : signals) s.data.push_back(kNaN);
  return frames() - 1;
}

namespace {
/// Keeps the even-numbered blocks of `stride` values (frames 0, 2, 4, ...).
template <class T>
void keep_even_blocks(std::vector<T>& v, std::size_t stride) {
  if (stride == 0) return;
  const std::size_t blocks = v.size() / stride;
  for (std::size_t f = 0; 2 * f < blocks; ++f)
    std::copy_n(v.begin() + static_cast<std::ptrdiff_t>(2 * f * stride), stride,
                v.begin() + static_cast<std::ptrdiff_t>(f * stride));
  v.resize((blocks + 1) / 2 * stride);
}
}  // namespace

void Scene::grow_layer(int layer, int count) {
  Layer& l = layers.at(static_cast<std::size_t>(layer));
  if (count <= l.count) return;
  const auto n = static_cast<std::size_t>(layer_item_floats(l.kind));
  const auto old_count = static_cast<std::size_t>(l.count), new_count = static_cast<std::size_t>(count);
  std::vector<float> data(static_cast<std::size_t>(frames()) * new_count * n, std::numeric_limits<float>::quiet_NaN());
  std::vector<std::uint8_t> color(static_cast<std::size_t>(frames()) * new_count, 0);
  for (std::size_t f = 0; f < static_cast<std::size_t>(frames()); ++f) {
    std::copy_n(l.data.begin() + static_cast<std::ptrdiff_t>(f * old_count * n), old_count * n,
                data.begin() + static_cast<std::ptrdiff_t>(f * new_count * n));
    std::copy_n(l.color.begin() + static_cast<std::ptrdiff_t>(f * old_count), old_count,
                color.begin() + static_cast<std::ptrdiff_t>(f * new_count));
  }
  l.count = count;
  l.data = std::move(data);
  l.color = std::move(color);
}

void Scene::drop_odd_frames() {
  keep_even_blocks(time, 1);
  keep_even_blocks(poses, bodies.size() * 7);
  for (Layer& l : layers) {
    keep_even_blocks(l.data, static_cast<std::size_t>(l.count * layer_item_floats(l.kind)));
    keep_even_blocks(l.color, static_cast<std::size_t>(l.count));
  }
  for (Signal& s : signals) keep_even_blocks(s.data, 1);
}

void Scene::set_pose(int frame, int body, const std::array<double, 3>& pos, const std::array<double, 4>& quat) {
  float* p = poses.data() + (static_cast<std::size_t>(frame) * bodies.size() + static_cast<std::size_t>(body)) * 7;
  for (int i = 0; i < 3; ++i) p[i] = static_cast<float>(pos[i]);
  for (int i = 0; i < 4; ++i) p[3 + i] = static_cast<float>(quat[i]);
}

void Scene::set_item(int layer, int frame, int k, const std::array<double, 3>& a, const std::array<double, 3>& b,
                     int color) {
  Layer& l = layers.at(static_cast<std::size_t>(layer));
  const int n = layer_item_floats(l.kind);
  float* p = l.data.data() + (static_cast<std::size_t>(frame) * l.count + static_cast<std::size_t>(k)) * n;
  for (int i = 0; i < 3; ++i) p[i] = static_cast<float>(a[i]);
  if (n == 6)
    for (int i = 0; i < 3; ++i) p[3 + i] = static_cast<float>(b[i]);
  l.color[static_cast<std::size_t>(frame) * l.count + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(color);
}

void Scene::set_signal(int signal, int frame, double value) {
  signals.at(static_cast<std::size_t>(signal)).data.at(static_cast<std::size_t>(frame)) = static_cast<float>(value);
}

void Scene::check() const {
  const auto f = static_cast<std::size_t>(frames());
  if (poses.size() != f * bodies.size() * 7) throw std::logic_error("replay scene: poses do not match frames × bodies");
  for (const Layer& l : layers) {
    if (l.data.size() != f * static_cast<std::size_t>(l.count * layer_item_floats(l.kind)) ||
        l.color.size() != f * static_cast<std::size_t>(l.count))
      throw std::logic_error("replay scene: layer " + l.name + " does not match the frames");
    for (std::uint8_t c : l.color)
      if (c >= l.palette.size())
        throw std::logic_error("replay scene: layer " + l.name + " colour outside its palette");
  }
  for (std::size_t i = 0; i < signals.size(); ++i) {
    const Signal& s = signals[i];
    if (s.data.size() != f) throw std::logic_error("replay scene: signal " + s.name + " does not match the frames");
    for (std::size_t k = 0; k < i; ++k) {  // (the page finds a signal by its name; a plot has one axis)
      if (signals[k].name == s.name) throw std::logic_error("replay scene: two signals named " + s.name);
      if (!s.plot.empty() && signals[k].panel == s.panel && signals[k].plot == s.plot && signals[k].unit != s.unit)
        throw std::logic_error("replay scene: plot " + s.plot + " has signals of different units");
    }
  }
}

std::string base64(const void* bytes, std::size_t size) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const unsigned char*>(bytes);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const unsigned v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    for (int s = 18; s >= 0; s -= 6) out.push_back(kAlphabet[(v >> s) & 63]);
  }
  if (i < size) {
    const unsigned v = (in[i] << 16) | (i + 1 < size ? in[i + 1] << 8 : 0);
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(i + 1 < size ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

std::vector<unsigned char> unbase64(std::string_view text) {
  if (text.size() % 4 != 0) throw std::invalid_argument("base64: length not a multiple of 4");
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::vector<unsigned char> out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    unsigned v = 0;
    int pad = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const char c = text[i + k];
      const int d = c == '=' && i + 4 == text.size() && k >= 2 ? (++pad, 0) : value(c);
      if (d < 0 || (pad > 0 && c != '=')) throw std::invalid_argument("base64: a character outside the alphabet");
      v = (v << 6) | static_cast<unsigned>(d);
    }
    out.push_back(static_cast<unsigned char>(v >> 16));
    if (pad < 2) out.push_back(static_cast<unsigned char>((v >> 8) & 0xff));
    if (pad < 1) out.push_back(static_cast<unsigned char>(v & 0xff));
  }
  return out;
}

namespace {

template <class T>
std::vector<T> from_b64(const nlohmann::json& j, const char* what) {
  if (!j.is_string()) throw std::invalid_argument(std::string("replay: ") + what + " is not a base64 string");
  const auto bytes = unbase64(j.get<std::string>());
  if (bytes.size() % sizeof(T) != 0)
    throw std::invalid_argument(std::string("replay: ") + what + " has a partial value");
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

template <class T>
std::string b64(const std::vector<T>& v) {
  return base64(v.data(), v.size() * sizeof(T));
}

nlohmann::ordered_json rgba_json(const std::array<float, 4>& c) {
  // float → shortest decimal of the float (3 digits suffice for a colour)
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (float v : c) a.push_back(std::round(static_cast<double>(v) * 1000) / 1000);
  return a;
}

nlohmann::ordered_json geom_json(const Geom& g) {
  nlohmann::ordered_json j;
  j["type"] = geom_type_name(g.type);
  j["size"] = g.size;
  j["pos"] = g.pos;
  j["quat"] = g.quat;
  j["rgba"] = rgba_json(g.rgba);
  if (g.checker) j["checker"] = true;
  if (g.type == GeomType::Mesh) {
    j["vertices"] = b64(g.vertices);
    j["faces"] = b64(g.faces);
  }
  return j;
}

}  // namespace

std::string replay_json(const Scene& scene) {
  scene.check();
  nlohmann::ordered_json j;
  j["format"] = "flexgait-replay";
  j["version"] = 1;
  j["title"] = scene.title;
  j["camera"] = {{"target", scene.camera.target},
                 {"distance", scene.camera.distance},
                 {"azimuth", scene.camera.azimuth},
                 {"elevation", scene.camera.elevation},
                 {"follow", scene.camera.follow}};
  j["shadow_extent"] = scene.shadow_extent;
  j["time"] = b64(scene.time);  // float64: a frame's time is its log row's, bit for bit
  j["statics"] = nlohmann::ordered_json::array();
  for (const Geom& g : scene.statics) j["statics"].push_back(geom_json(g));
  j["bodies"] = nlohmann::ordered_json::array();
  for (const Body& b : scene.bodies) {
    nlohmann::ordered_json geoms = nlohmann::ordered_json::array();
    for (const Geom& g : b.geoms) geoms.push_back(geom_json(g));
    j["bodies"].push_back({{"name", b.name}, {"geoms", geoms}});
  }
  j["poses"] = b64(scene.poses);
  j["layers"] = nlohmann::ordered_json::array();
  for (const Layer& l : scene.layers) {
    nlohmann::ordered_json lj;
    lj["name"] = l.name;
    lj["kind"] = layer_kind_name(l.kind);
    lj["count"] = l.count;
    lj["width"] = l.width;
    lj["turns"] = l.turns;
    lj["palette"] = nlohmann::ordered_json::array();
    for (const auto& c : l.palette) lj["palette"].push_back(rgba_json(c));
    lj["legend"] = l.legend;
    lj["visible"] = l.visible;
    lj["data"] = b64(l.data);
    lj["color"] = b64(l.color);
    j["layers"].push_back(lj);
  }
  j["signals"] = nlohmann::ordered_json::array();
  for (const Signal& s : scene.signals)
    j["signals"].push_back({{"name", s.name},
                            {"unit", s.unit},
                            {"panel", s.panel},
                            {"plot", s.plot},
                            {"label", s.label},
                            {"data", b64(s.data)}});
  std::string text = j.dump();
  // Inside <script>: "</" could end the element early; "<\/" is the same JSON string.
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out.push_back(text[i]);
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out.push_back('\\');
  }
  return out;
}

namespace {

GeomType geom_type(const std::string& name) {
  for (GeomType t : {GeomType::Plane, GeomType::Sphere, GeomType::Capsule, GeomType::Ellipsoid, GeomType::Cylinder,
                     GeomType::Box, GeomType::Mesh})
    if (name == geom_type_name(t)) return t;
  throw std::invalid_argument("replay: unknown geom type " + name);
}

Geom geom_from(const nlohmann::json& j) {
  Geom g;
  g.type = geom_type(j.at("type").get<std::string>());
  g.size = j.at("size").get<std::array<double, 3>>();
  g.pos = j.at("pos").get<std::array<double, 3>>();
  g.quat = j.at("quat").get<std::array<double, 4>>();
  g.rgba = j.at("rgba").get<std::array<float, 4>>();
  g.checker = j.value("checker", false);
  if (g.type == GeomType::Mesh) {
    g.vertices = from_b64<float>(j.at("vertices"), "a mesh's vertices");
    g.faces = from_b64<std::uint32_t>(j.at("faces"), "a mesh's faces");
  }
  return g;
}

}  // namespace

Scene parse_replay_html(std::string_view html) {
  constexpr std::string_view kOpen = R"(<script id="flexgait-replay-data" type="application/json">)";
  const std::size_t at = html.find(kOpen);
  const std::size_t end = at == std::string_view::npos ? at : html.find("</script>", at);
  if (end == std::string_view::npos) throw std::invalid_argument("no flexgait replay data block in the page");
  const std::string_view block = html.substr(at + kOpen.size(), end - at - kOpen.size());
  Scene s;
  try {
    const auto j = nlohmann::json::parse(block);
    if (j.value("format", "") != "flexgait-replay" || j.value("version", 0) != 1)
      throw std::invalid_argument("replay: not format flexgait-replay version 1");
    s.title = j.value("title", "");
    const auto& c = j.at("camera");
    s.camera = {c.at("target").get<std::array<double, 3>>(), c.at("distance").get<double>(),
                c.at("azimuth").get<double>(), c.at("elevation").get<double>(), c.value("follow", "")};
    s.shadow_extent = j.value("shadow_extent", 6.0);
    s.time = from_b64<double>(j.at("time"), "time");
    for (const auto& g : j.at("statics")) s.statics.push_back(geom_from(g));
    for (const auto& b : j.at("bodies")) {
      Body body{b.at("name").get<std::string>(), {}};
      for (const auto& g : b.at("geoms")) body.geoms.push_back(geom_from(g));
      s.bodies.push_back(std::move(body));
    }
    s.poses = from_b64<float>(j.at("poses"), "poses");
    for (const auto& lj : j.at("layers")) {
      Layer l;
      l.name = lj.at("name").get<std::string>();
      const std::string kind = lj.at("kind").get<std::string>();
      bool known = false;
      for (LayerKind k : {LayerKind::Segments, LayerKind::Springs, LayerKind::Arrows, LayerKind::Points})
        if (kind == layer_kind_name(k)) l.kind = k, known = true;
      if (!known) throw std::invalid_argument("replay: unknown layer kind " + kind);
      l.count = lj.at("count").get<int>();
      l.width = lj.at("width").get<double>();
      l.turns = lj.value("turns", 10);
      l.palette = lj.at("palette").get<std::vector<std::array<float, 4>>>();
      l.legend = lj.value("legend", std::vector<std::string>{});
      l.visible = lj.value("visible", true);
      l.data = from_b64<float>(lj.at("data"), "a layer's items");
      l.color = from_b64<std::uint8_t>(lj.at("color"), "a layer's colours");
      s.layers.push_back(std::move(l));
    }
    for (const auto& sj : j.at("signals"))
      s.signals.push_back({sj.at("name").get<std::string>(), sj.value("unit", ""),
                           from_b64<float>(sj.at("data"), "a signal"), sj.value("panel", ""), sj.value("plot", ""),
                           sj.value("label", "")});
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("replay data block: ") + e.what());
  }
  try {
    s.check();
  } catch (const std::logic_error& e) {
    throw std::invalid_argument(e.what());
  }
  return s;
}

bool replay_page_available() {
  return detail::kReplayTemplateSize > 1;
}

std::string replay_html(const Scene& scene) {
  if (!replay_page_available())
    throw std::runtime_error("this flexgait was built without the replay page (FLEXGAIT_REPLAY=OFF)");
  const std::string_view page(reinterpret_cast<const char*>(detail::kReplayTemplate), detail::kReplayTemplateSize);
  constexpr std::string_view kPlaceholder = "@FLEXGAIT_REPLAY_DATA@";
  const std::size_t at = page.find(kPlaceholder);
  if (at == std::string_view::npos) throw std::logic_error("replay page template without its data placeholder");
  std::string html(page.substr(0, at));
  html += replay_json(scene);
  html += page.substr(at + kPlaceholder.size());
  return html;
}

}  // namespace flexgait::replay
