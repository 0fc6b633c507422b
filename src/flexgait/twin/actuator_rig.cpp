#include "flexgait/twin/actuator_rig.hpp"

#include <fmt/format.h>

#include <vector>

#include "flexgait/twin/detail/elastic_drives.hpp"
#include "flexgait/twin/detail/mujoco.hpp"

namespace flexgait::twin {
namespace {

// A fixed actuator housing, a hinge about +y and a light arm along +x carrying a point load.
std::string rig_mjcf(const ActuatorRigParams& p) {
  return fmt::format(R"(<mujoco model="flexgait_stiffness_bench">
  <compiler angle="radian" inertiafromgeom="true"/>
  <option timestep="{dt}" integrator="Euler" gravity="0 0 -{g}"/>
  <worldbody>
    <body name="arm" pos="0 0 1">
      <joint name="joint" type="hinge" axis="0 1 0" stiffness="{k}" damping="{d}"/>
      <geom type="capsule" fromto="0 0 0 {l} 0 0" size="0.01" mass="0.001" contype="0" conaffinity="0"/>
      <geom type="sphere" pos="{l} 0 0" size="0.03" mass="{m}" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>
)",
                     fmt::arg("dt", p.physics_dt), fmt::arg("g", p.gravity), fmt::arg("k", p.actuator.k),
                     fmt::arg("d", p.actuator.d), fmt::arg("l", p.arm_length), fmt::arg("m", p.load_mass));
}

}  // namespace

struct ActuatorRig::Impl {
  explicit Impl(const ActuatorRigParams& p) : m(load_mjcf(rig_mjcf(p))), drive(m, {0}, {p.actuator}) {
    drive.take_springs(m);
    d = mj_makeData(m);
  }
  ~Impl() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  mjModel* m;
  ElasticDrives drive;
  mjData* d = nullptr;
  std::vector<ActuatorState> motor;
};

ActuatorRig::ActuatorRig(const ActuatorRigParams& params, double link_angle) : impl_(std::make_unique<Impl>(params)) {
  impl_->d->qpos[0] = link_angle;
  mj_forward(impl_->m, impl_->d);
  impl_->motor = impl_->drive.at_rest(impl_->d);
}

ActuatorRig::~ActuatorRig() = default;

void ActuatorRig::step(double command) {
  impl_->drive.step(impl_->m, impl_->d, impl_->motor, &command);
}
double ActuatorRig::link_angle() const {
  return impl_->d->qpos[0];
}
const ActuatorState& ActuatorRig::motor() const {
  return impl_->motor[0];
}
int ActuatorRig::warnings() const {
  return mujoco_warning_count(impl_->d);
}
std::string ActuatorRig::warnings_text() const {
  return mujoco_warnings_text(impl_->d);
}

}  // namespace flexgait::twin
