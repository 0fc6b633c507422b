// flexgait.HumanoidLoop and flexgait.Controller: the humanoid's closed loop stepped from Python, with
// the builtin walking controller or a controller written in Python (docs/guide/loop.md).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "flexgait/experiments/walk_experiment.hpp"
#include "flexgait/twin/renderer.hpp"

namespace flexgait::python {
namespace {

using humanoid::kJoints;

template <std::size_t N>
py::array_t<double> array_of(const std::array<double, N>& values) {
  py::array_t<double> a(static_cast<py::ssize_t>(N));
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

template <std::size_t N, std::size_t M>
py::array_t<double> array_of(const std::array<std::array<double, M>, N>& rows) {
  py::array_t<double> a({static_cast<py::ssize_t>(N), static_cast<py::ssize_t>(M)});
  for (std::size_t i = 0; i < N; ++i)
    std::copy(rows[i].begin(), rows[i].end(), a.mutable_data(static_cast<py::ssize_t>(i), 0));
  return a;
}

/// A joint command from Python: a float array of kJoints finite values, else ValueError naming `what`.
humanoid::JointVector joint_command(const py::handle& value, const char* what) {
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 1 || a.shape(0) != kJoints)
    throw py::value_error(fmt::format("{}: expected {} joint angles [rad] (HumanoidLoop.joint_names order), got {}",
                                      what, kJoints, std::string(py::str(py::repr(value)))));
  humanoid::JointVector q{};
  for (int j = 0; j < kJoints; ++j) {
    q[j] = a.at(j);
    if (!std::isfinite(q[j]))
      throw py::value_error(fmt::format("{}: joint {} ({}) is {}; allowed: a finite angle [rad]", what, j,
                                        humanoid::kJointNames[static_cast<std::size_t>(j)], q[j]));
  }
  return q;
}

/// The trampoline: Controller subclasses in Python implement update(sensors, t).
class PyController : public loop::Controller {
 public:
  humanoid::JointVector update(const humanoid::SensorReadings& sensors, double t) override {
    py::gil_scoped_acquire gil;
    const py::function f = py::get_override(static_cast<const loop::Controller*>(this), "update");
    if (!f) throw py::type_error("flexgait.Controller.update(sensors, t) is not implemented by the subclass");
    return joint_command(f(sensors, t), "Controller.update's return");
  }
  void sent(const humanoid::JointVector& command) override {
    py::gil_scoped_acquire gil;
    if (const py::function f = py::get_override(static_cast<const loop::Controller*>(this), "sent"))
      f(array_of(command));
  }
};

/// flexgait.HumanoidLoop: the run's configuration, the loop, its controller, a renderer when asked.
class PyHumanoidLoop {
 public:
  /// \param controller None (the builtin walking controller) or a flexgait.Controller; the loop keeps
  /// the Python object alive with it (its update is Python's as long as the loop runs).
  PyHumanoidLoop(const py::object& config, const std::optional<std::string>& config_file, const py::object& controller)
      : config_(make_config(experiments::walk_run_schema(), config, config_file)),
        params_(experiments::walk_run_from_config(config_)) {
    if (!controller.is_none()) {
      if (!py::isinstance<loop::Controller>(controller))
        throw py::type_error("controller: expected None or a flexgait.Controller, got " +
                             std::string(py::str(controller.get_type().attr("__name__"))));
      controller_object_ = controller;
      user_ = controller.cast<std::shared_ptr<loop::Controller>>();
    }
    reset(std::nullopt);
  }

  void reset(const std::optional<long long>& seed) {
    if (seed) {
      if (*seed < 0 || *seed > 2147483647LL)
        throw py::value_error(fmt::format("seed: {} is not in [0, 2147483647]", *seed));
      params_.plant.noise_seed = static_cast<int>(*seed);
    }
    renderer_.reset();
    walk_ = experiments::make_walk_loop(params_, user_);  // the user's controller, if any, in the builtin's place
  }

  void step(const py::object& command) {
    std::optional<loop::SimulationFailure> failure;
    if (command.is_none()) {
      py::gil_scoped_release release;
      failure = walk_.loop->step();
    } else {
      const humanoid::JointVector q = joint_command(command, "command");
      py::gil_scoped_release release;
      failure = walk_.loop->step(q);
    }
    if (failure)
      throw std::runtime_error(fmt::format(
          "the simulation failed at t = {:.6g} s: {}{}", walk_.loop->time(), name_of(*failure),
          *failure == loop::SimulationFailure::kMuJoCoWarning ? " (" + walk_.loop->plant().warnings_text() + ")"
                                                              : std::string()));
  }

  /// Steps until time `until` [s] (default: the builtin plan's end) with the loop's controller.
  void run(std::optional<double> until) {
    const double end = until ? *until : walk_.control->controller().plan().duration;
    if (!std::isfinite(end)) throw py::value_error("until: must be a finite time [s]");
    const double T = params_.plant.control_period;
    InterruptCheck interrupted;
    while (walk_.loop->time() + 0.5 * T < end) {
      std::optional<loop::SimulationFailure> failure;
      {
        py::gil_scoped_release release;
        for (int i = 0; i < 250 && walk_.loop->time() + 0.5 * T < end && !failure; ++i) failure = walk_.loop->step();
      }
      if (failure) step(py::none());  // raises the failure's message (the loop refuses to go on)
      interrupted();
    }
  }

  py::array render(int width, int height) {
    if (width < 1 || height < 1)
      throw py::value_error(fmt::format("render: width and height must be >= 1, got {}x{}", width, height));
    if (!renderer_ || renderer_->width() != width || renderer_->height() != height)
      renderer_ = std::make_unique<twin::Renderer>(walk_.loop->plant(), width, height);
    std::vector<unsigned char> rgb;
    {
      py::gil_scoped_release release;
      rgb = renderer_->render(walk_.loop->plant());
    }
    py::array_t<unsigned char> image({height, width, 3});
    std::copy(rgb.begin(), rgb.end(), image.mutable_data());
    return image;
  }

  const loop::HumanoidLoop& loop() const { return *walk_.loop; }
  const experiments::WalkRunParams& params() const { return params_; }
  const Config& config() const { return config_; }
  const walking::WalkingController& builtin() const { return walk_.control->controller(); }
  bool builtin_in_control() const { return !user_; }

 private:
  Config config_;
  experiments::WalkRunParams params_;
  py::object controller_object_;  ///< the Python side of user_ (its overrides live there)
  std::shared_ptr<loop::Controller> user_;
  experiments::WalkLoop walk_;
  std::unique_ptr<twin::Renderer> renderer_;
};

py::list joint_names() {
  py::list names;
  for (const auto& n : humanoid::kJointNames) names.append(py::str(std::string(n)));
  return names;
}

void bind_records(py::module_& m) {
  py::class_<humanoid::SensorReadings>(
      m, "SensorReadings",
      "What a controller reads in one period (SI units): motor-side encoders, the servos' torque from their "
      "current, the ankle F/T sensors (force on the foot from the leg, foot frame) and the pelvis IMU.")
      .def_property_readonly(
          "t", [](const humanoid::SensorReadings& s) { return s.t; }, "time [s]")
      .def_property_readonly(
          "encoder", [](const humanoid::SensorReadings& s) { return array_of(s.encoder); },
          "motor-side encoder angles [rad], joint_names order")
      .def_property_readonly(
          "encoder_stamp", [](const humanoid::SensorReadings& s) { return array_of(s.encoder_stamp); },
          "when each encoder was read [s]")
      .def_property_readonly(
          "motor_torque", [](const humanoid::SensorReadings& s) { return array_of(s.motor_torque); },
          "each servo's torque from its motor current, averaged over the control period [N m]")
      .def_property_readonly(
          "ft_force",
          [](const humanoid::SensorReadings& s) {
            return array_of(std::array<std::array<double, 3>, 2>{s.ft[0].force, s.ft[1].force});
          },
          "left, right ankle force [N] (2x3)")
      .def_property_readonly(
          "ft_torque",
          [](const humanoid::SensorReadings& s) {
            return array_of(std::array<std::array<double, 3>, 2>{s.ft[0].torque, s.ft[1].torque});
          },
          "left, right ankle torque [N m] (2x3)")
      .def_property_readonly(
          "imu_quat", [](const humanoid::SensorReadings& s) { return array_of(s.imu.quat); },
          "AHRS pelvis orientation (w, x, y, z), world frame")
      .def_property_readonly(
          "gyro", [](const humanoid::SensorReadings& s) { return array_of(s.imu.gyro); },
          "pelvis angular rate, pelvis frame [rad/s]")
      .def_property_readonly(
          "accel", [](const humanoid::SensorReadings& s) { return array_of(s.imu.accel); },
          "specific force, pelvis frame [m/s^2] (+g up at rest)")
      .def_property_readonly(
          "delta_angle", [](const humanoid::SensorReadings& s) { return array_of(s.imu.delta_angle); },
          "the pelvis's turn since the last reading, integrated inside the IMU, pelvis frame [rad]");
  py::class_<twin::GroundTruth>(m, "GroundTruth",
                                "The twin's true state (for evaluation; a controller is not given it).")
      .def_property_readonly(
          "t", [](const twin::GroundTruth& g) { return g.t; }, "time [s]")
      .def_property_readonly(
          "link_angle", [](const twin::GroundTruth& g) { return array_of(g.link_angle); }, "[rad]")
      .def_property_readonly(
          "link_velocity", [](const twin::GroundTruth& g) { return array_of(g.link_velocity); }, "[rad/s]")
      .def_property_readonly(
          "motor_angle", [](const twin::GroundTruth& g) { return array_of(g.motor_angle); }, "[rad]")
      .def_property_readonly(
          "gear_torque", [](const twin::GroundTruth& g) { return array_of(g.gear_torque); }, "[N m]")
      .def_property_readonly(
          "servo_torque", [](const twin::GroundTruth& g) { return array_of(g.servo_torque); },
          "the motors' servo torque, within each joint's limit [N m]")
      .def_property_readonly(
          "pelvis_pos", [](const twin::GroundTruth& g) { return array_of(g.pelvis_pos); }, "[m]")
      .def_property_readonly(
          "pelvis_quat", [](const twin::GroundTruth& g) { return array_of(g.pelvis_quat); }, "(w, x, y, z)")
      .def_property_readonly(
          "com", [](const twin::GroundTruth& g) { return array_of(g.com); }, "whole-body COM [m]")
      .def_property_readonly(
          "zmp", [](const twin::GroundTruth& g) { return array_of(g.zmp); },
          "floor contacts' centre of pressure (x, y) [m]")
      .def_property_readonly(
          "sole_pos", [](const twin::GroundTruth& g) { return array_of(g.sole_pos); },
          "left, right sole centres [m] (2x3)")
      .def_property_readonly(
          "sole_contact",
          [](const twin::GroundTruth& g) {
            return std::vector<bool>{g.sole_contact[0], g.sole_contact[1]};
          },
          "each sole touches the floor")
      .def_property_readonly(
          "non_sole_contact", [](const twin::GroundTruth& g) { return g.non_sole_contact; },
          "a body other than a sole touches the floor")
      .def_property_readonly(
          "normal_force", [](const twin::GroundTruth& g) { return g.normal_force; }, "[N]")
      .def_property_readonly(
          "warnings", [](const twin::GroundTruth& g) { return g.warnings; }, "MuJoCo warnings so far");
}

}  // namespace

void bind_loop(py::module_& m) {
  bind_records(m);
  py::class_<loop::Controller, PyController, std::shared_ptr<loop::Controller>>(
      m, "Controller",
      "Base class of a controller written in Python: implement update(self, sensors, t) returning the joint "
      "commands (13 motor-side angles [rad], HumanoidLoop.joint_names order); optionally sent(self, command), "
      "told the command the servos received (after the compensators and joint ranges).")
      .def(py::init<>())
      .def("update", &loop::Controller::update, py::arg("sensors"), py::arg("t"));
  py::class_<PyHumanoidLoop>(
      m, "HumanoidLoop",
      "The humanoid's closed loop on the MuJoCo twin, one control period per step(): the twin (plant, terrain, "
      "pushes, sensors with their faults), a controller (the builtin walking controller, or `controller`, a "
      "flexgait.Controller), and the deformation compensators on its command as `config` sets them "
      "(control.compensation). `config`: a dict of keys (nested dicts allowed) as for flexgait.humanoid.walk.")
      .def(py::init<const py::object&, const std::optional<std::string>&, const py::object&>(),
           py::arg("config") = py::none(), py::arg("config_file") = py::none(), py::arg("controller") = py::none())
      .def("reset", &PyHumanoidLoop::reset, py::arg("seed") = py::none(),
           "Back to the start pose at t = 0 (a new twin; `seed` replaces plant.noise.seed: the same seed, the same "
           "run).")
      .def("step", &PyHumanoidLoop::step, py::arg("command") = py::none(),
           "One control period. command=None: the loop's controller decides; else 13 desired joint angles [rad] "
           "in joint_names order, passed through the compensators as configured. Releases the GIL. Raises "
           "ValueError for a wrong shape or a non-finite angle, RuntimeError when the simulation fails (and on "
           "any step after that until reset).")
      .def("run", &PyHumanoidLoop::run, py::arg("until") = py::none(),
           "Steps with the loop's controller until time `until` [s] (default: the builtin plan's end), GIL released.")
      .def(
          "sensors", [](const PyHumanoidLoop& l) { return l.loop().sensors(); },
          "The sensors' readings now (SensorReadings).")
      .def(
          "truth", [](const PyHumanoidLoop& l) { return l.loop().truth(); }, "The twin's true state now (GroundTruth).")
      .def(
          "command", [](const PyHumanoidLoop& l) { return array_of(l.loop().command()); },
          "The last command sent [rad].")
      .def("render", &PyHumanoidLoop::render, py::arg("width") = 640, py::arg("height") = 480,
           "The twin now as an RGB image, a uint8 array (height, width, 3) (MuJoCo offscreen, OSMesa).")
      .def_property_readonly(
          "time", [](const PyHumanoidLoop& l) { return l.loop().time(); }, "simulated time [s]")
      .def_property_readonly(
          "period", [](const PyHumanoidLoop& l) { return l.params().plant.control_period; }, "control period [s]")
      .def_property_readonly(
          "duration", [](const PyHumanoidLoop& l) { return l.builtin().plan().duration; },
          "the builtin walking plan's length [s]")
      .def_property_readonly(
          "initial_pose", [](const PyHumanoidLoop& l) { return array_of(l.builtin().initial_pose()); },
          "the start pose [rad]")
      .def_property_readonly_static(
          "joint_names", [](const py::object&) { return joint_names(); }, "the joints, in command order")
      .def_property_readonly("config", [](const PyHumanoidLoop& l) { return config_dict(l.config()); });
}

}  // namespace flexgait::python
