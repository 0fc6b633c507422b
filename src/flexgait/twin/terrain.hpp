#pragma once
/// \file terrain.hpp
/// The twin's floor (docs/guide/humanoid.md): flat (the default, the MJCF of earlier versions byte for byte), a
/// ramp, a single step or a rough floor. The controller is told nothing about it; it feels the
/// floor through its sensors only.
///
/// Geometry (world frame, x forward, z up; floor height h(x, y) [m]):
/// - flat:  h = 0 (a MuJoCo plane).
/// - ramp:  h = 0 for x < x_r, h = (x − x_r) tan α beyond (α = terrain.ramp.angle, > 0 uphill in
///          +x; x_r = terrain.ramp.start). Two boxes: a level one ending at x_r, a tilted one
///          hinged on the level one's top edge.
/// - step:  h = 0 for x < x_s, h = h_s beyond (x_s = terrain.step.x, h_s = terrain.step.height,
///          < 0 a step down). Two boxes meeting at x = x_s.
/// - rough: a MuJoCo height field over x ∈ [kRoughXMin, kRoughXMax], |y| ≤ kRoughHalfWidth (the
///          floor ends there), nodes every `cell` metres. Heights: white noise N(0, 1) on the
///          nodes (std::mt19937_64 seeded by terrain.rough.seed), smoothed by a Gaussian kernel of
///          standard deviation ℓ/2 (so the field's autocorrelation is exp(−r²/ℓ²), ℓ =
///          terrain.rough.correlation), then scaled so that max |h| = A (terrain.rough.amplitude).
///          MuJoCo triangulates each cell; h here interpolates bilinearly, exact on the nodes.
#include <array>
#include <string>
#include <vector>

#include "flexgait/core/record.hpp"

namespace flexgait::twin {

enum class TerrainKind { kFlat, kRamp, kStep, kRough };
constexpr std::array<EnumName<TerrainKind>, 4> enum_names(TerrainKind) {
  return {{{TerrainKind::kFlat, "flat"},
           {TerrainKind::kRamp, "ramp"},
           {TerrainKind::kStep, "step"},
           {TerrainKind::kRough, "rough"}}};
}

struct TerrainParams {
  TerrainKind kind = TerrainKind::kFlat;
  double ramp_angle = 0.0;         ///< α [rad], > 0: uphill along +x
  double ramp_start = 0.2;         ///< x_r, where the ramp begins [m]
  double step_height = 0.0;        ///< h_s [m], < 0: a step down
  double step_x = 0.35;            ///< x_s, the step's edge [m]
  double rough_amplitude = 0.01;   ///< A, largest |h| [m]
  double rough_correlation = 0.1;  ///< ℓ [m]
  int rough_seed = 1;
  bool known_heights = false;  ///< the walking controller is told the floor's heights at its footprints

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("terrain.kind", s.kind,
      {.doc = "floor: flat, ramp (terrain.ramp.*), step (terrain.step.*) or rough (terrain.rough.*)"});
    v("terrain.ramp.angle", s.ramp_angle,
      {.unit = "rad", .doc = "ramp slope (> 0: uphill along +x; 0.0349 = 2 deg)", .bounds = closed(-0.35, 0.35)});
    v("terrain.ramp.start", s.ramp_start,
      {.unit = "m", .doc = "x where the ramp begins (level floor before)", .bounds = closed(-5, 5)});
    v("terrain.step.height", s.step_height,
      {.unit = "m",
       .doc = "height of the step (< 0: a step down; within the legs' reach)",
       .bounds = closed(-0.3, 0.3)});
    v("terrain.step.x", s.step_x, {.unit = "m", .doc = "x of the step's edge", .bounds = closed(-5, 5)});
    v("terrain.rough.amplitude", s.rough_amplitude,
      {.unit = "m", .doc = "rough floor: largest |height|", .bounds = left_open(0, 0.1)});
    v("terrain.rough.correlation", s.rough_correlation,
      {.unit = "m",
       .doc = "rough floor: correlation length (autocorrelation exp(-r^2/l^2))",
       .bounds = closed(0.02, 1)});
    v("terrain.rough.seed", s.rough_seed, {.doc = "rough floor: seed of its heights", .bounds = closed(0, 2147483647)});
    v("terrain.known_heights", s.known_heights,
      {.doc = "the controller is told the floor's heights at its footprints (else it feels the floor through its "
              "sensors only)"});
  }
};

/// The rough floor's extent [m] (x from kRoughXMin to kRoughXMax, |y| ≤ kRoughHalfWidth).
inline constexpr double kRoughXMin = -2.0, kRoughXMax = 8.0, kRoughHalfWidth = 1.5;

/// The rough floor's nodes: ncol along x, nrow along y, row-major from (kRoughXMin, −kRoughHalfWidth)
/// (MuJoCo's hfield_data layout).
struct HeightGrid {
  int nrow = 0, ncol = 0;
  double cell = 0;             ///< node spacing [m]
  std::vector<double> height;  ///< [m], nrow × ncol
};

/// Node spacing of the rough floor: 2 cm, or ℓ/2 for a shorter correlation length [m].
double rough_cell(const TerrainParams& params);

/// The floor of `params`, with its rough heights generated once.
class Terrain {
 public:
  explicit Terrain(const TerrainParams& params);
  const TerrainParams& params() const { return params_; }
  /// Floor height under (x, y) [m] (see the file comment; the rough floor's edge: 0 outside).
  double height(double x, double y) const;
  /// The rough floor's nodes (empty for another kind).
  const HeightGrid& grid() const { return grid_; }

 private:
  TerrainParams params_;
  HeightGrid grid_;
};

/// The floor as MJCF: `asset` (the height field's element, inside <asset>, or "") and `geoms`
/// (world geoms, the first named "floor", the others floor_1, ...; material flexgait_floor, which the
/// document around them defines (the checkered floor); friction and the contact's
/// time constant as the soles'). The height field's data is not in the text: MuJoCo 2.2 reads it
/// from a file only, so the plant writes Terrain::grid() into the model's hfield_data.
struct TerrainMjcf {
  std::string asset, geoms;
};
TerrainMjcf terrain_mjcf(const TerrainParams& params, double friction, double contact_time_constant);

/// Name of the rough floor's height field in the MJCF.
inline constexpr const char* kTerrainHfield = "terrain";

}  // namespace flexgait::twin
