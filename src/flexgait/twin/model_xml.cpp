#include "flexgait/twin/model_xml.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cstring>
#include <memory>
#include <stdexcept>

#include "flexgait/robot/builtin_inertials.hpp"
#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::twin {
namespace {

std::string joint(const std::string& name, const char* axis, double k, double d, const char* range = nullptr) {
  return fmt::format(R"(<joint name="{}" type="hinge" axis="{}" stiffness="{}" damping="{}"{}/>)", name, axis, k, d,
                     range ? fmt::format(R"( range="{}")", range) : "");
}

/// <inertial> of a body: THORMANG3's numbers at full precision (builtin_inertials.hpp), as
/// principal moments and axes — the form the loader writes back (twin_mjcf.hpp), so that a loaded
/// export compiles to the same numbers.
std::string inertial(const humanoid::BodyInertial& b) {
  const auto& c = b.com;
  const auto& i = b.inertia;  // ixx ixy ixz iyy iyz izz
  Eigen::Matrix3d I;
  I << i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) *= -1;
  const Eigen::Quaterniond q(axes);
  const Eigen::Vector3d d = eig.eigenvalues();
  return fmt::format(R"(<inertial pos="{} {} {}" mass="{}" quat="{} {} {} {}" diaginertia="{} {} {}"/>)", c[0], c[1],
                     c[2], b.mass, q.w(), q.x(), q.y(), q.z(), d[0], d[1], d[2]);
}

std::string leg(const humanoid::RobotParams& r, const PlantParams& p, const std::array<humanoid::BodyInertial, 7>& in,
                int side) {
  const humanoid::JointVector k = p.gear_stiffness();
  const char* s = side == 0 ? "l" : "r";
  const double y = side == 0 ? r.hip_yaw_offset_y : -r.hip_yaw_offset_y;
  const int j0 = humanoid::leg_first_joint(side);
  const double d = p.gear_damping;
  const double sole_h = r.sole_thickness;
  return fmt::format(R"(
      <body name="{s}_hip_yaw_link" pos="0 {y} {zy}">
        {i0}
        {j_yaw}
        <geom type="cylinder" size="0.035 0.03" pos="0 0 -0.03"/>
        <body name="{s}_hip_roll_link" pos="0 0 {zr}">
          {i1}
          {j_roll}
          <geom type="box" size="0.05 0.04 0.035"/>
          <body name="{s}_thigh" pos="0 0 0">
            {i2}
            {j_pitch}
            <geom type="capsule" fromto="0 0 -0.04 0 0 {thigh_end}" size="0.05"/>
            <body name="{s}_shank" pos="0 0 {thigh}">
              {i3}
              {j_knee}
              <geom type="capsule" fromto="0 0 -0.04 0 0 {shank_end}" size="0.045"/>
              <body name="{s}_ankle_pitch_link" pos="0 0 {shank}">
                {i4}
                {j_ap}
                <geom type="box" size="0.04 0.04 0.03"/>
                <body name="{s}_ankle_roll_link" pos="0 0 0">
                  {i5}
                  {j_ar}
                  <geom type="box" size="0.03 0.03 0.02"/>
                  <body name="{s}_foot" pos="0 0 0">
                    {i6}
                    <site name="{s}_ft" pos="0 0 0" size="0.01"/>
                    <geom name="{s}_sole" type="box" pos="0 {sole_y} {sole_z}" size="{half_l} {half_w} {half_h}"
                          contype="1" conaffinity="1" condim="3" friction="{mu} 0.005 0.0001" solref="{tc} 1" rgba=".3 .3 .8 1"/>
                  </body>
                </body>
              </body>
            </body>
          </body>
        </body>
      </body>)",
                     fmt::arg("s", s), fmt::arg("y", y), fmt::arg("zy", -r.hip_yaw_offset_z),
                     fmt::arg("i0", inertial(in[0])), fmt::arg("i1", inertial(in[1])), fmt::arg("i2", inertial(in[2])),
                     fmt::arg("i3", inertial(in[3])), fmt::arg("i4", inertial(in[4])), fmt::arg("i5", inertial(in[5])),
                     fmt::arg("i6", inertial(in[6])),
                     fmt::arg("j_yaw", joint(std::string(s) + "_hip_yaw", "0 0 1", k[j0 + 0], d)),
                     fmt::arg("zr", -(r.hip_axes_depth - r.hip_yaw_offset_z)),
                     fmt::arg("j_roll", joint(std::string(s) + "_hip_roll", "1 0 0", k[j0 + 1], d)),
                     fmt::arg("j_pitch", joint(std::string(s) + "_hip_pitch", "0 1 0", k[j0 + 2], d)),
                     fmt::arg("thigh_end", -r.thigh + 0.04), fmt::arg("thigh", -r.thigh),
                     fmt::arg("j_knee", joint(std::string(s) + "_knee", "0 1 0", k[j0 + 3], d)),
                     fmt::arg("shank_end", -r.shank + 0.04), fmt::arg("shank", -r.shank),
                     fmt::arg("j_ap", joint(std::string(s) + "_ankle_pitch", "0 1 0", k[j0 + 4], d)),
                     fmt::arg("j_ar", joint(std::string(s) + "_ankle_roll", "1 0 0", k[j0 + 5], d)),
                     fmt::arg("sole_y", side == 0 ? r.sole_offset_y : -r.sole_offset_y),
                     fmt::arg("sole_z", -(r.ankle_to_sole - 0.5 * sole_h)), fmt::arg("half_l", 0.5 * r.sole_length),
                     fmt::arg("half_w", 0.5 * r.sole_width), fmt::arg("half_h", 0.5 * sole_h),
                     fmt::arg("mu", r.sole_friction), fmt::arg("tc", p.contact_time_constant));
}

}  // namespace

std::string humanoid_mjcf(const humanoid::RobotParams& r, const PlantParams& p) {
  const humanoid::JointVector k = p.gear_stiffness();
  const humanoid::BuiltinInertials in = humanoid::builtin_inertials(r);
  const std::string pelvis = fmt::format(
      R"(    <body name="pelvis" pos="0 0 1">
      <freejoint name="root"/>
      {i_pelvis}
      <site name="imu" pos="0 0 0" size="0.01"/>
      <geom type="box" size="0.09 0.14 0.05" pos="0 0 0"/>
      <body name="chest" pos="0 0 {chest_z}">
        {i_chest}
        {j_waist}
        <geom type="box" size="0.11 0.15 0.14" pos="0 0 {chest_com}"/>
        <geom name="l_arm" type="capsule" fromto="0 {arm_y} {arm_top} 0 {arm_y} {arm_bottom}" size="0.045"/>
        <geom name="r_arm" type="capsule" fromto="0 -{arm_y} {arm_top} 0 -{arm_y} {arm_bottom}" size="0.045"/>
        <geom name="head" type="sphere" size="0.1" pos="0 0 {head_z}"/>
      </body>{left}{right}
    </body>
)",
      fmt::arg("i_pelvis", inertial(in.pelvis)), fmt::arg("i_chest", inertial(in.chest)),
      fmt::arg("j_waist", joint("waist_yaw", "0 0 1", k[humanoid::kWaistYaw], p.gear_damping)),
      fmt::arg("chest_z", r.chest_joint_z), fmt::arg("chest_com", r.chest_com_z), fmt::arg("arm_y", r.arm_y),
      fmt::arg("arm_top", r.arm_com_z + 0.24), fmt::arg("arm_bottom", r.arm_com_z - 0.24), fmt::arg("head_z", r.head_z),
      fmt::arg("left", leg(r, p, in.leg[0], 0)), fmt::arg("right", leg(r, p, in.leg[1], 1)));
  return twin_document("flexgait_thormang_twin", false, r.sole_friction, humanoid::kDefaultGravity, p, pelvis, "");
}

std::string look_visual_mjcf(int width, int height) {
  return fmt::format(R"(  <visual>
    <global offwidth="{}" offheight="{}"/>
    <quality shadowsize="4096"/>
    <headlight ambient=".3 .3 .3" diffuse=".35 .35 .35" specular="0 0 0"/>
  </visual>
)",
                     width, height);
}

std::string look_assets_mjcf() {
  return R"(    <texture name="flexgait_sky" type="skybox" builtin="gradient" rgb1=".42 .6 .85" rgb2=".93 .95 .98" width="256" height="1536"/>
    <texture name="flexgait_grid" type="2d" builtin="checker" rgb1=".86 .87 .84" rgb2=".72 .75 .71" mark="edge" markrgb=".35 .35 .35" width="512" height="512"/>
    <material name="flexgait_floor" texture="flexgait_grid" texrepeat="1 1" texuniform="true"/>
)";
}

std::string twin_document(const std::string& model, bool inertia_from_geom, double sole_friction, double gravity,
                          const PlantParams& p, const std::string& bodies, const std::string& contact) {
  const TerrainMjcf floor = terrain_mjcf(p.terrain, sole_friction, p.contact_time_constant);
  return fmt::format(R"(<mujoco model="{model}">
  <compiler angle="radian" inertiafromgeom="{ifg}" autolimits="true"/>
  <option timestep="{dt}" integrator="Euler" solver="Newton" iterations="100" tolerance="1e-10" gravity="0 0 -{g}"/>
  <size nconmax="200" njmax="600"/>
  <default>
    <geom contype="0" conaffinity="0" rgba=".75 .75 .75 1"/>
    <site rgba="1 0 0 1"/>
  </default>
{visual}  <asset>
{look}{asset}  </asset>
  <worldbody>
    <light pos="0 -2 4" dir="0 0.4 -1" directional="true" castshadow="true" diffuse=".75 .75 .75"/>
{floor}{bodies}  </worldbody>
{contact}  <sensor>
    <force name="l_ft_force" site="l_ft"/>
    <torque name="l_ft_torque" site="l_ft"/>
    <force name="r_ft_force" site="r_ft"/>
    <torque name="r_ft_torque" site="r_ft"/>
    <framequat name="imu_quat" objtype="site" objname="imu"/>
    <gyro name="imu_gyro" site="imu"/>
    <accelerometer name="imu_acc" site="imu"/>
  </sensor>
</mujoco>
)",
                     fmt::arg("asset", floor.asset), fmt::arg("visual", look_visual_mjcf(1280, 720)),
                     fmt::arg("look", look_assets_mjcf()), fmt::arg("floor", floor.geoms), fmt::arg("model", model),
                     fmt::arg("ifg", inertia_from_geom ? "true" : "false"), fmt::arg("dt", p.physics_dt),
                     fmt::arg("g", gravity), fmt::arg("bodies", bodies), fmt::arg("contact", contact));
}

mjModel* load_mjcf(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "flexgait_model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo VFS: cannot create the model file");
  const int i = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[i], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (m == nullptr) throw std::runtime_error(std::string("MuJoCo could not load the model: ") + error);
  return m;
}

}  // namespace flexgait::twin
