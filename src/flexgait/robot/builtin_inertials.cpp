#include "flexgait/robot/builtin_inertials.hpp"

#include <Eigen/Geometry>

#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "flexgait/robot/thormang3_inertials.hpp"

namespace flexgait::humanoid {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

/// A link placed in a body frame: its frame's origin there and its rotation.
struct Placed {
  std::string link;
  Vector3d origin = Vector3d::Zero();
  Matrix3d rotation = Matrix3d::Identity();
};

Matrix3d tensor(const std::array<double, 6>& i) {
  Matrix3d t;
  t << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
  return t;
}

/// The links lumped into one body: total mass, common centre, inertia about it (parallel axes),
/// plus point masses (mass, position) that add no inertia of their own.
BodyInertial lump(const std::vector<Placed>& links, const std::vector<std::pair<double, Vector3d>>& points = {}) {
  double m = 0;
  Vector3d c = Vector3d::Zero();
  struct Part {
    double m;
    Vector3d c;
    Matrix3d I;
  };
  std::vector<Part> parts;
  for (const Placed& p : links) {
    const Thormang3Link& l = thormang3_link(p.link);
    parts.push_back({l.mass, p.origin + p.rotation * Vector3d(l.com[0], l.com[1], l.com[2]),
                     p.rotation * tensor(l.inertia) * p.rotation.transpose()});
  }
  for (const auto& [mass, at] : points) parts.push_back({mass, at, Matrix3d::Zero()});
  for (const Part& p : parts) {
    m += p.m;
    c += p.m * p.c;
  }
  c /= m;
  Matrix3d I = Matrix3d::Zero();
  for (const Part& p : parts) {
    const Vector3d d = p.c - c;
    I += p.I + p.m * (d.squaredNorm() * Matrix3d::Identity() - d * d.transpose());
  }
  BodyInertial b;
  b.mass = m;
  b.com = {c.x(), c.y(), c.z()};
  b.inertia = {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)};
  return b;
}

Vector3d com_of(std::string_view link) {
  const auto& c = thormang3_link(link).com;
  return {c[0], c[1], c[2]};
}

/// One arm in the chest frame (ROBOTIS's joint origins, thormang3_kinematics_dynamics), turned
/// about its shoulder-roll axis so that it hangs. `s` = +1 left, −1 right.
std::vector<Placed> arm(double s) {
  const std::string p = s > 0 ? "l_arm_" : "r_arm_";
  const Vector3d sh_p1(0, s * 0.152, 0.160);
  const Vector3d sh_r = sh_p1 + Vector3d(0.057, s * 0.060, -0.039);
  const Vector3d sh_p2 = sh_r + Vector3d(-0.057, s * 0.033, 0);
  const Vector3d el_y = sh_p2 + Vector3d(0.030, s * 0.187, 0.057);
  const Vector3d wr_r = el_y + Vector3d(0.171, s * 0.030, -0.057);
  const Vector3d wr_y = wr_r + Vector3d(0.039, 0, 0.045);
  const Vector3d wr_p = wr_y + Vector3d(0.045, -s * 0.045, -0.045);
  const Vector3d grip = wr_p + Vector3d(0.088, s * 0.058, 0), grip_1 = wr_p + Vector3d(0.088, s * 0.032, 0);
  // Upper arm along ±y in the zero pose: −90° (left) / +90° (right) about x brings it to −z.
  const Matrix3d R = Eigen::AngleAxisd(-s * 0.5 * std::numbers::pi, Vector3d::UnitX()).toRotationMatrix();
  auto turned = [&](const char* link, const Vector3d& origin) {
    return Placed{p + link, sh_r + R * (origin - sh_r), R};
  };
  return {Placed{p + "sh_p1", sh_p1, Matrix3d::Identity()},
          turned("sh_r", sh_r),
          turned("sh_p2", sh_p2),
          turned("el_y", el_y),
          turned("wr_r", wr_r),
          turned("wr_y", wr_y),
          turned("wr_p", wr_p),
          turned("grip", grip),
          turned("grip_1", grip_1)};
}

}  // namespace

BuiltinInertials builtin_inertials(const RobotParams& r) {
  const double extra = r.total_mass - thormang3_mass();  // batteries and computers [kg]
  if (extra < -1e-9) throw std::invalid_argument("robot.total_mass is below THORMANG3's links' 42.533 kg");
  BuiltinInertials b;
  b.pelvis = lump({{"pelvis"}}, {{0.5 * extra, com_of("pelvis")}});
  std::vector<Placed> upper = {
      {"torso_y"}, {"head_y", Vector3d(0, 0, 0.229)}, {"head_p", Vector3d(0, -0.045, 0.229 + 0.039)}};
  for (double s : {1.0, -1.0})
    for (const Placed& p : arm(s)) upper.push_back(p);
  b.chest = lump(upper, {{0.5 * extra, com_of("torso_y")}});
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? 1.0 : -1.0;  // outward is +y on the left
    const std::string p = side == 0 ? "l_leg_" : "r_leg_";
    const std::array<std::pair<std::string, Vector3d>, 7> links = {{
        {p + "hip_y", Vector3d::Zero()},
        {p + "hip_r", Vector3d(0.057, 0, 0)},
        {p + "hip_p", Vector3d(0, s * 0.033, 0)},
        {p + "kn_p", Vector3d(0, s * 0.093, 0)},
        {p + "an_p", Vector3d(0, s * 0.033, 0)},
        {p + "an_r", Vector3d(0.057, 0, 0)},
        {p + "foot", Vector3d(0, 0, -(r.ankle_to_sole - 0.0275))},
    }};
    for (int i = 0; i < 7; ++i) b.leg[side][i] = lump({{links[i].first, links[i].second}});
  }
  return b;
}

}  // namespace flexgait::humanoid
