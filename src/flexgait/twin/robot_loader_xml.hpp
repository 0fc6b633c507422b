#pragma once
/// \file robot_loader_xml.hpp
/// The attributes of description text (MJCF or URDF) as written, with their line numbers, for the
/// checks the loader makes before MuJoCo's compiler reads the file (numbers MuJoCo would take
/// silently: NaN, infinities; attributes of MuJoCo versions newer than the twin's). A small
/// scanner of XML's tag syntax (comments, processing instructions, CDATA and DOCTYPE skipped), not
/// a validating parser: MuJoCo's compiler remains the judge of the document's structure.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace flexgait::twin {

/// One attribute of one element start tag.
struct XmlAttribute {
  std::string_view element;  ///< the element's name
  std::string_view name;     ///< the attribute's name
  std::string_view value;    ///< its value as written (entities not expanded)
  int line = 1;              ///< line of the attribute's name (1-based)
  std::size_t begin = 0;     ///< offset of the attribute's name in the text
  std::size_t end = 0;       ///< offset just past its closing quote
  std::size_t tag = 0;       ///< offset of the element's '<'
};

/// Calls `visit` for every attribute of every start tag of `text`, in document order. Stops at the
/// first tag that is not closed (the compiler reports it).
void for_each_xml_attribute(std::string_view text, const std::function<void(const XmlAttribute&)>& visit);

/// Whether the attribute names another element or a file (its value is text, never a number).
bool names_something(std::string_view attribute);

/// The first whitespace-separated token of `value` that reads as a number but not a finite one
/// (nan, inf, infinity in any case and sign, or an overflowing literal such as 1e999); "" if none.
std::string non_finite_token(std::string_view value);

/// MJCF text written for MuJoCo 3 made readable by the twin's MuJoCo (2.2.2), where 2.2.2 has an
/// equivalent or the attribute only concerns what the twin replaces (its own integrator, its own
/// drives, its own viewer):
///   integrator="implicitfast"       → "implicit" (the twin sets its own integrator anyway);
///   actuatorfrcrange (joints): renamed `user` when joint_force_ranges_as_user(text), so that MuJoCo's compiler
///   resolves it through the default classes and the loader reads it as the joint's torque limit; else dropped;
///   actuatorfrclimited, actuatorgravcomp (joints), inheritrange, kv
///   (actuators), ellipsoidinertia (visual/global): dropped (the twin drives the joints itself);
///   no autolimits on <compiler>: autolimits="true", MuJoCo 3's default (a range then limits).
/// Returns the translated text (each line where it was) and appends one warning per attribute
/// (naming it, its first line and how many times it was met). Anything else 2.2.2 does not know
/// is left for its compiler to refuse, naming the attribute and the line.
///
/// Also: a <mesh> whose file is not found (relative to `dir` and the compiler's meshdir) is
/// dropped with the geoms that show it, one warning in all (the robot's masses come from its
/// <inertial> elements; a foot whose contact geoms were meshes needs the mapping's sole_size).
/// `kPlaceholder` instead: each missing mesh becomes a small inline tetrahedron and every geom stays
/// (to learn which geoms showed a missing mesh, with their classes' contact bits resolved), no
/// warning about them. `missing_names`, when given, receives the missing meshes' names.
enum class MissingMeshes { kDrop, kPlaceholder };

/// Whether translate_mujoco3 carries the joints' actuatorfrcrange (MuJoCo 3: the clamp of the total actuator force
/// at a joint) in their `user` numbers: the text gives some joint (or joint default) an actuatorfrcrange and none a
/// `user` attribute, nor sets nuser_jnt (the file's own user data would be overwritten).
bool joint_force_ranges_as_user(std::string_view text);
std::string translate_mujoco3(std::string_view text, std::vector<std::string>& warnings, const std::string& dir = "",
                              MissingMeshes missing_meshes = MissingMeshes::kDrop,
                              std::vector<std::string>* missing_names = nullptr);

}  // namespace flexgait::twin
