#include "flexgait/twin/model_xml.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <cstring>
#include <memory>
#include <stdexcept>

#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::humanoid {
namespace {

std::string joint(const std::string& name, const char* axis, double k, double d, const char* range = nullptr) {
  return fmt::format(R"(<joint name="{}" type="hinge" axis="{}" stiffness="{}" damping="{}"{}/>)", name, axis, k, d,
                     range ? fmt::format(R"( range="{}")", range) : "");
}

std::string leg(const RobotParams& r, const PlantParams& p, int side) {
  const JointVector k = p.gear_stiffness();
  const char* s = side == 0 ? "l" : "r";
  const double y = side == 0 ? r.hip_yaw_offset_y : -r.hip_yaw_offset_y;
  const int j0 = leg_first_joint(side);
  const double d = p.gear_damping;
  const double sole_h = r.sole_thickness;
  return fmt::format(R"(
      <body name="{s}_hip_yaw_link" pos="0 {y} {zy}">
        {j_yaw}
        <geom type="cylinder" size="0.035 0.03" pos="0 0 {com_yaw}" mass="{m_yaw}"/>
        <body name="{s}_hip_roll_link" pos="0 0 {zr}">
          {j_roll}
          <geom type="box" size="0.05 0.04 0.035" mass="{m_roll}"/>
          <body name="{s}_thigh" pos="0 0 0">
            {j_pitch}
            <geom type="capsule" fromto="0 0 -0.04 0 0 {thigh_end}" size="0.05" mass="{m_thigh}"/>
            <body name="{s}_shank" pos="0 0 {thigh}">
              {j_knee}
              <geom type="capsule" fromto="0 0 -0.04 0 0 {shank_end}" size="0.045" mass="{m_shank}"/>
              <body name="{s}_ankle_pitch_link" pos="0 0 {shank}">
                {j_ap}
                <geom type="box" size="0.04 0.04 0.03" mass="{m_ap}"/>
                <body name="{s}_ankle_roll_link" pos="0 0 0">
                  {j_ar}
                  <geom type="box" size="0.03 0.03 0.02" mass="{m_ar}"/>
                  <body name="{s}_foot" pos="0 0 0">
                    <site name="{s}_ft" pos="0 0 0" size="0.01"/>
                    <geom name="{s}_sole" type="box" pos="0 0 {sole_z}" size="{half_l} {half_w} {half_h}" mass="{m_foot}"
                          contype="1" conaffinity="1" condim="3" friction="{mu} 0.005 0.0001" solref="{tc} 1" rgba=".3 .3 .8 1"/>
                  </body>
                </body>
              </body>
            </body>
          </body>
        </body>
      </body>)",
      fmt::arg("s", s), fmt::arg("y", y), fmt::arg("zy", -r.hip_yaw_offset_z),
      fmt::arg("j_yaw", joint(std::string(s) + "_hip_yaw", "0 0 1", k[j0 + 0], d)),
      fmt::arg("m_yaw", r.m_hip_yaw), fmt::arg("com_yaw", r.hip_yaw_com_z), fmt::arg("zr", -(r.hip_axes_depth - r.hip_yaw_offset_z)),
      fmt::arg("j_roll", joint(std::string(s) + "_hip_roll", "1 0 0", k[j0 + 1], d)),
      fmt::arg("m_roll", r.m_hip_roll),
      fmt::arg("j_pitch", joint(std::string(s) + "_hip_pitch", "0 1 0", k[j0 + 2], d)),
      fmt::arg("thigh_end", -r.thigh + 0.04), fmt::arg("m_thigh", r.m_thigh), fmt::arg("thigh", -r.thigh),
      fmt::arg("j_knee", joint(std::string(s) + "_knee", "0 1 0", k[j0 + 3], d)),
      fmt::arg("shank_end", -r.shank + 0.04), fmt::arg("m_shank", r.m_shank), fmt::arg("shank", -r.shank),
      fmt::arg("j_ap", joint(std::string(s) + "_ankle_pitch", "0 1 0", k[j0 + 4], d)),
      fmt::arg("m_ap", r.m_ankle_pitch),
      fmt::arg("j_ar", joint(std::string(s) + "_ankle_roll", "1 0 0", k[j0 + 5], d)),
      fmt::arg("m_ar", r.m_ankle_roll), fmt::arg("sole_z", -(r.ankle_to_sole - 0.5 * sole_h)),
      fmt::arg("half_l", 0.5 * r.sole_length), fmt::arg("half_w", 0.5 * r.sole_width), fmt::arg("half_h", 0.5 * sole_h),
      fmt::arg("m_foot", r.m_foot), fmt::arg("mu", r.sole_friction), fmt::arg("tc", p.contact_time_constant));
}

}  // namespace

std::string humanoid_mjcf(const RobotParams& r, const PlantParams& p) {
  const JointVector k = p.gear_stiffness();
  const double extra = r.total_mass - r.listed_mass();  // batteries and computers [kg]
  if (extra < -1e-9) throw std::invalid_argument("robot.total_mass is below the sum of the listed links");
  const std::string pelvis = fmt::format(R"(    <body name="pelvis" pos="0 0 1">
      <freejoint name="root"/>
      <site name="imu" pos="0 0 0" size="0.01"/>
      <geom type="box" size="0.09 0.14 0.05" pos="0 0 0" mass="{m_pelvis}"/>
      <body name="chest" pos="0 0 {chest_z}">
        {j_waist}
        <geom type="box" size="0.11 0.15 0.14" pos="0 0 {chest_com}" mass="{m_chest}"/>
        <geom name="l_arm" type="capsule" fromto="0 {arm_y} {arm_top} 0 {arm_y} {arm_bottom}" size="0.045" mass="{m_arm}"/>
        <geom name="r_arm" type="capsule" fromto="0 -{arm_y} {arm_top} 0 -{arm_y} {arm_bottom}" size="0.045" mass="{m_arm}"/>
        <geom name="head" type="sphere" size="0.1" pos="0 0 {head_z}" mass="{m_head}"/>
      </body>{left}{right}
    </body>
)",
                                         fmt::arg("m_pelvis", r.m_pelvis + 0.5 * extra), fmt::arg("m_chest", r.m_chest + 0.5 * extra),
                                         fmt::arg("j_waist", joint("waist_yaw", "0 0 1", k[kWaistYaw], p.gear_damping)),
                                         fmt::arg("chest_z", r.chest_joint_z), fmt::arg("chest_com", r.chest_com_z),
                                         fmt::arg("arm_y", r.arm_y), fmt::arg("arm_top", r.arm_com_z + 0.24),
                                         fmt::arg("arm_bottom", r.arm_com_z - 0.24), fmt::arg("head_z", r.head_z),
                                         fmt::arg("m_arm", r.m_arm), fmt::arg("m_head", r.m_head), fmt::arg("left", leg(r, p, 0)),
                                         fmt::arg("right", leg(r, p, 1)));
  return twin_document("flexgait_thormang_twin", true, r.sole_friction, p, pelvis, "");
}

std::string twin_document(const std::string& model, bool inertia_from_geom, double sole_friction, const PlantParams& p,
                          const std::string& bodies, const std::string& contact) {
  const TerrainMjcf floor = terrain_mjcf(p.terrain, sole_friction, p.contact_time_constant);
  return fmt::format(R"(<mujoco model="{model}">
  <compiler angle="radian" inertiafromgeom="{ifg}" autolimits="true"/>
  <option timestep="{dt}" integrator="Euler" solver="Newton" iterations="100" tolerance="1e-10" gravity="0 0 -9.81"/>
  <size nconmax="200" njmax="600"/>
  <default>
    <geom contype="0" conaffinity="0" rgba=".75 .75 .75 1"/>
    <site rgba="1 0 0 1"/>
  </default>
  <visual><global offwidth="1280" offheight="720"/></visual>
{asset}  <worldbody>
    <light pos="0 -2 4" dir="0 0.4 -1" directional="true"/>
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
                     fmt::arg("asset", floor.asset.empty() ? "" : "  <asset>\n" + floor.asset + "  </asset>\n"),
                     fmt::arg("floor", floor.geoms), fmt::arg("model", model), fmt::arg("ifg", inertia_from_geom ? "true" : "false"),
                     fmt::arg("dt", p.physics_dt),
                     fmt::arg("bodies", bodies), fmt::arg("contact", contact));
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

}  // namespace flexgait::humanoid
