#include "flexgait/twin/terrain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace flexgait::twin {
namespace {

constexpr double kBoxHalfLength = 10.0;  ///< half-length of the ramp's and step's boxes along x [m]
constexpr double kBoxHalfWidth = 10.0;   ///< [m]
constexpr double kBoxHalfHeight = 0.5;   ///< [m]

/// A level box along x from x0 to x1 whose top face is at z = top.
std::string level_box(const std::string& name, double x0, double x1, double top, const std::string& contact) {
  return fmt::format(R"(    <geom name="{}" type="box" size="{} {} {}" pos="{} 0 {}" {}/>
)",
                     name, 0.5 * (x1 - x0), kBoxHalfWidth, kBoxHalfHeight, 0.5 * (x0 + x1), top - kBoxHalfHeight,
                     contact);
}

/// The nodes of the rough floor (terrain.hpp: smoothed white noise scaled to max |h| = A).
HeightGrid rough_grid(const TerrainParams& p) {
  HeightGrid g;
  g.cell = rough_cell(p);
  g.ncol = static_cast<int>(std::lround((kRoughXMax - kRoughXMin) / g.cell)) + 1;
  g.nrow = static_cast<int>(std::lround(2 * kRoughHalfWidth / g.cell)) + 1;
  // Gaussian kernel of standard deviation ℓ/2 (in nodes), cut at 3 σ; the noise is drawn on a
  // margin of that radius so that the field is as rough at its edges as inside.
  const double sigma = 0.5 * p.rough_correlation / g.cell;
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
  for (int i = -radius; i <= radius; ++i)
    kernel[static_cast<std::size_t>(i + radius)] = std::exp(-0.5 * i * i / (sigma * sigma));
  const int rows = g.nrow + 2 * radius, cols = g.ncol + 2 * radius;
  std::vector<double> noise(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols));
  std::mt19937_64 rng(static_cast<std::uint64_t>(p.rough_seed));
  std::normal_distribution<double> unit(0.0, 1.0);
  for (double& n : noise) n = unit(rng);
  // Separable convolution: along x (columns) on every padded row, then along y (rows).
  std::vector<double> along_x(static_cast<std::size_t>(rows) * static_cast<std::size_t>(g.ncol));
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < g.ncol; ++c) {
      double s = 0;
      for (int i = 0; i <= 2 * radius; ++i)
        s += kernel[static_cast<std::size_t>(i)] * noise[static_cast<std::size_t>(r * cols + c + i)];
      along_x[static_cast<std::size_t>(r * g.ncol + c)] = s;
    }
  g.height.assign(static_cast<std::size_t>(g.nrow) * static_cast<std::size_t>(g.ncol), 0.0);
  double peak = 0;
  for (int r = 0; r < g.nrow; ++r)
    for (int c = 0; c < g.ncol; ++c) {
      double s = 0;
      for (int i = 0; i <= 2 * radius; ++i)
        s += kernel[static_cast<std::size_t>(i)] * along_x[static_cast<std::size_t>((r + i) * g.ncol + c)];
      g.height[static_cast<std::size_t>(r * g.ncol + c)] = s;
      peak = std::max(peak, std::abs(s));
    }
  for (double& h : g.height) h *= p.rough_amplitude / peak;
  return g;
}

}  // namespace

double rough_cell(const TerrainParams& p) {
  return std::min(0.02, 0.5 * p.rough_correlation);
}

Terrain::Terrain(const TerrainParams& params) : params_(params) {
  if (params_.kind == TerrainKind::kRough) grid_ = rough_grid(params_);
}

double Terrain::height(double x, double y) const {
  const TerrainParams& p = params_;
  switch (p.kind) {
    case TerrainKind::kFlat:
      return 0.0;
    case TerrainKind::kRamp:
      return x < p.ramp_start ? 0.0 : (x - p.ramp_start) * std::tan(p.ramp_angle);
    case TerrainKind::kStep:
      return x < p.step_x ? 0.0 : p.step_height;
    case TerrainKind::kRough: {
      // Bilinear between the four nodes around (x, y); outside, the nearest edge.
      const double u = std::clamp((x - kRoughXMin) / grid_.cell, 0.0, grid_.ncol - 1.0);
      const double v = std::clamp((y + kRoughHalfWidth) / grid_.cell, 0.0, grid_.nrow - 1.0);
      const int c = std::min(static_cast<int>(u), grid_.ncol - 2), r = std::min(static_cast<int>(v), grid_.nrow - 2);
      const double fu = u - c, fv = v - r;
      auto at = [&](int rr, int cc) { return grid_.height[static_cast<std::size_t>(rr * grid_.ncol + cc)]; };
      return (1 - fv) * ((1 - fu) * at(r, c) + fu * at(r, c + 1)) +
             fv * ((1 - fu) * at(r + 1, c) + fu * at(r + 1, c + 1));
    }
  }
  return 0.0;
}

TerrainMjcf terrain_mjcf(const TerrainParams& p, double mu, double tc) {
  const std::string contact = fmt::format(
      R"(contype="1" conaffinity="1" friction="{} 0.005 0.0001" solref="{} 1" material="flexgait_floor")", mu, tc);
  TerrainMjcf out;
  switch (p.kind) {
    case TerrainKind::kFlat:
      out.geoms = fmt::format("    <geom name=\"floor\" type=\"plane\" size=\"20 20 0.1\" {}/>\n", contact);
      break;
    case TerrainKind::kRamp: {
      // The tilted box hinged on the level box's top edge (x_r, 0): its centre is the hinge plus
      // R_y(−α) (L, 0, −H), the rotation that lifts +x by α.
      const double a = p.ramp_angle, c = std::cos(a), s = std::sin(a);
      const double cx = p.ramp_start + kBoxHalfLength * c + kBoxHalfHeight * s;
      const double cz = kBoxHalfLength * s - kBoxHalfHeight * c;
      out.geoms =
          level_box("floor", p.ramp_start - 2 * kBoxHalfLength, p.ramp_start, 0.0, contact) +
          fmt::format(
              "    <geom name=\"floor_1\" type=\"box\" size=\"{} {} {}\" pos=\"{} 0 {}\" axisangle=\"0 1 0 {}\" {}/>\n",
              kBoxHalfLength, kBoxHalfWidth, kBoxHalfHeight, cx, cz, -a, contact);
      break;
    }
    case TerrainKind::kStep:
      out.geoms = level_box("floor", p.step_x - 2 * kBoxHalfLength, p.step_x, 0.0, contact) +
                  level_box("floor_1", p.step_x, p.step_x + 2 * kBoxHalfLength, p.step_height, contact);
      break;
    case TerrainKind::kRough: {
      // Heights −A + 2A·data with data ∈ [0, 1] (HumanoidPlant writes it from Terrain::grid()).
      const double cell = rough_cell(p);
      const int ncol = static_cast<int>(std::lround((kRoughXMax - kRoughXMin) / cell)) + 1;
      const int nrow = static_cast<int>(std::lround(2 * kRoughHalfWidth / cell)) + 1;
      out.asset =
          fmt::format("    <hfield name=\"{}\" nrow=\"{}\" ncol=\"{}\" size=\"{} {} {} 0.1\"/>\n", kTerrainHfield, nrow,
                      ncol, 0.5 * (kRoughXMax - kRoughXMin), kRoughHalfWidth, 2 * p.rough_amplitude);
      out.geoms = fmt::format("    <geom name=\"floor\" type=\"hfield\" hfield=\"{}\" pos=\"{} 0 {}\" {}/>\n",
                              kTerrainHfield, 0.5 * (kRoughXMin + kRoughXMax), -p.rough_amplitude, contact);
      break;
    }
  }
  return out;
}

}  // namespace flexgait::twin
