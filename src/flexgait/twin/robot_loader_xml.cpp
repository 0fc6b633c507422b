#include "flexgait/twin/robot_loader_xml.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <fmt/format.h>

namespace flexgait::twin {
namespace {

bool space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}
bool name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == ':' || c == '-' || c == '.';
}

}  // namespace

void for_each_xml_attribute(std::string_view text, const std::function<void(const XmlAttribute&)>& visit) {
  std::size_t i = 0;
  int line = 1;
  auto advance_to = [&](std::size_t to) {  // moves i to `to`, counting line ends
    to = std::min(to, text.size());
    line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i),
                                        text.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
    i = to;
  };
  auto skip_past = [&](std::string_view close) {
    const std::size_t at = text.find(close, i);
    advance_to(at == std::string_view::npos ? text.size() : at + close.size());
    return at != std::string_view::npos;
  };
  while (i < text.size()) {
    const std::size_t lt = text.find('<', i);
    if (lt == std::string_view::npos) return;
    advance_to(lt);
    const std::string_view rest = text.substr(i);
    if (rest.starts_with("<!--")) {
      if (!skip_past("-->")) return;
    } else if (rest.starts_with("<![CDATA[")) {
      if (!skip_past("]]>")) return;
    } else if (rest.starts_with("<?")) {
      if (!skip_past("?>")) return;
    } else if (rest.starts_with("<!") || rest.starts_with("</")) {
      if (!skip_past(">")) return;
    } else {
      const std::size_t tag = i;
      advance_to(i + 1);
      const std::size_t name_begin = i;
      while (i < text.size() && name_char(text[i])) ++i;
      const std::string_view element = text.substr(name_begin, i - name_begin);
      for (;;) {
        while (i < text.size() && space(text[i])) advance_to(i + 1);
        if (i >= text.size()) return;
        if (text[i] == '>' || text[i] == '/') break;
        XmlAttribute a;
        a.tag = tag;
        a.element = element;
        a.line = line;
        a.begin = i;
        while (i < text.size() && name_char(text[i])) ++i;
        a.name = text.substr(a.begin, i - a.begin);
        while (i < text.size() && space(text[i])) advance_to(i + 1);
        if (a.name.empty() || i >= text.size() || text[i] != '=') return;  // not XML: the compiler says so
        advance_to(i + 1);
        while (i < text.size() && space(text[i])) advance_to(i + 1);
        if (i >= text.size() || (text[i] != '"' && text[i] != '\'')) return;
        const char quote = text[i];
        const std::size_t close = text.find(quote, i + 1);
        if (close == std::string_view::npos) return;
        a.value = text.substr(i + 1, close - i - 1);
        advance_to(close + 1);
        a.end = i;
        visit(a);
      }
      if (!skip_past(">")) return;
    }
  }
}

bool names_something(std::string_view a) {
  static constexpr std::array<std::string_view, 33> kNames = {
      "name",       "class",    "childclass", "file",     "filename", "link",    "mesh",  "material", "texture",
      "hfield",     "joint",    "joint1",     "joint2",   "body",     "body1",   "body2", "geom",     "geom1",
      "geom2",      "site",     "tendon",     "actuator", "target",   "objname", "model", "prefix",   "meshdir",
      "texturedir", "assetdir", "parent",     "child",    "version",  "xmlns"};
  return std::find(kNames.begin(), kNames.end(), a) != kNames.end();
}

std::string non_finite_token(std::string_view value) {
  std::size_t i = 0;
  while (i < value.size()) {
    while (i < value.size() && space(value[i])) ++i;
    const std::size_t begin = i;
    while (i < value.size() && !space(value[i])) ++i;
    if (i == begin) break;
    const std::string token(value.substr(begin, i - begin));
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(token.c_str(), &end);
    if (end == token.c_str() + token.size() && !std::isfinite(x)) return token;
  }
  return {};
}

bool joint_force_ranges_as_user(std::string_view text) {
  bool ranges = false, user = false;
  for_each_xml_attribute(text, [&](const XmlAttribute& a) {
    if (a.element == "joint" && a.name == "actuatorfrcrange") ranges = true;
    if ((a.element == "joint" && a.name == "user") || a.name == "nuser_jnt") user = true;
  });
  return ranges && !user;
}

std::string translate_mujoco3(std::string_view text, std::vector<std::string>& warnings, const std::string& dir,
                              MissingMeshes missing_meshes, std::vector<std::string>* missing_names) {
  struct Edit {
    std::size_t begin, end;
    std::string with;
  };
  std::vector<Edit> edits;
  struct Seen {
    int line = 0, count = 0;
    std::string what;
  };
  std::map<std::string, Seen> seen;  // by attribute, in name order (the same warnings for the same file)
  auto note = [&](const XmlAttribute& a, const std::string& what) {
    Seen& s = seen[std::string(a.name) + (a.name == "integrator" ? "=" + std::string(a.value) : "")];
    if (s.count++ == 0) {
      s.line = a.line;
      s.what = what;
    }
  };
  std::size_t compiler = std::string_view::npos, root_end = std::string_view::npos;
  bool autolimits = false;
  // Meshes whose files are absent: their elements and the geoms that show them are dropped.
  std::string meshdir;
  for_each_xml_attribute(text, [&](const XmlAttribute& a) {
    if (a.element == "compiler" && a.name == "meshdir") meshdir = std::string(a.value);
  });
  std::vector<std::string> missing;  // mesh names
  int missing_line = 0;
  std::size_t mesh_tag = std::string_view::npos;
  std::string mesh_name, mesh_file;
  std::array<std::size_t, 2> file_attribute{};  // [begin, end) of the file="..." attribute
  auto end_of_tag = [&](std::size_t tag) { return text.find('>', tag) + 1; };
  auto close_mesh = [&]() {
    if (mesh_tag == std::string_view::npos || mesh_file.empty()) return;
    const std::filesystem::path f = std::filesystem::path(dir) / meshdir / mesh_file;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(f, ec)) {
      missing.push_back(mesh_name.empty() ? std::filesystem::path(mesh_file).stem().string() : mesh_name);
      if (missing_meshes == MissingMeshes::kPlaceholder)  // a tetrahedron with 10 mm edges
        edits.push_back({file_attribute[0], file_attribute[1], R"(vertex="0 0 0 0.01 0 0 0 0.01 0 0 0 0.01")"});
      else
        edits.push_back({mesh_tag, end_of_tag(mesh_tag), ""});
    }
  };
  for_each_xml_attribute(text, [&](const XmlAttribute& a) {
    if (a.tag != mesh_tag) {
      close_mesh();
      mesh_tag = std::string_view::npos;
    }
    if (a.element == "mesh") {
      if (mesh_tag != a.tag) mesh_name.clear(), mesh_file.clear();
      mesh_tag = a.tag;
      if (a.name == "name") mesh_name = std::string(a.value);
      if (a.name == "file") {
        mesh_file = std::string(a.value);
        file_attribute = {a.begin, a.end};
        if (missing_line == 0) missing_line = a.line;
      }
    }
  });
  close_mesh();
  if (missing_names != nullptr) *missing_names = missing;
  if (!missing.empty() && missing_meshes == MissingMeshes::kDrop) {
    int geoms = 0;
    for_each_xml_attribute(text, [&](const XmlAttribute& a) {
      if (a.element == "geom" && a.name == "mesh" &&
          std::find(missing.begin(), missing.end(), a.value) != missing.end()) {
        edits.push_back({a.tag, end_of_tag(a.tag), ""});
        ++geoms;
      }
    });
    warnings.push_back(
        fmt::format("line {}: {} mesh files not found (first: {}); they and the {} geoms showing them "
                    "are dropped",
                    missing_line, missing.size(), missing.front(), geoms));
  }
  const bool ranges_as_user = joint_force_ranges_as_user(text);
  for_each_xml_attribute(text, [&](const XmlAttribute& a) {
    if (a.element == "compiler") {
      compiler = a.tag;
      autolimits = autolimits || a.name == "autolimits";
    }
    if (a.element == "option" && a.name == "integrator" && a.value == "implicitfast") {
      const std::size_t v = text.find(a.value, a.begin);
      edits.push_back({v, v + a.value.size(), "implicit"});
      note(a, "taken as \"implicit\" (MuJoCo 2.2.2 has no implicitfast; the twin sets its own integrator)");
    } else if (a.element == "joint" && a.name == "actuatorfrcrange" && ranges_as_user) {
      edits.push_back({a.begin, a.begin + a.name.size(), "user"});
      note(a, "read as the joint's torque limit (MuJoCo 3: the clamp of the actuators' force at the joint)");
    } else if ((a.element == "joint" &&
                (a.name == "actuatorfrcrange" || a.name == "actuatorfrclimited" || a.name == "actuatorgravcomp")) ||
               a.name == "inheritrange" || a.name == "kv" || (a.element == "global" && a.name == "ellipsoidinertia")) {
      edits.push_back({a.begin, a.end, ""});
      note(a, "dropped (MuJoCo 3; the twin drives the joints and draws the robot itself)");
    }
  });
  // <compiler> without autolimits: MuJoCo 3's default, a range limits its joint.
  if (!autolimits) {
    const std::size_t mujoco = text.find("<mujoco");
    if (compiler != std::string_view::npos) {
      edits.push_back({compiler + 9, compiler + 9, " autolimits=\"true\""});
    } else if (mujoco != std::string_view::npos && (root_end = text.find('>', mujoco)) != std::string_view::npos &&
               text[root_end - 1] != '/') {
      edits.push_back({root_end + 1, root_end + 1, "<compiler autolimits=\"true\"/>"});
    }
  }
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin > b.begin; });
  std::string out(text);
  for (const Edit& e : edits) out.replace(e.begin, e.end - e.begin, e.with);
  for (const auto& [name, s] : seen)
    warnings.push_back(fmt::format("line {}: {} {}{}", s.line, name, s.what,
                                   s.count > 1 ? fmt::format(" ({} times)", s.count) : std::string()));
  return out;
}

}  // namespace flexgait::twin
