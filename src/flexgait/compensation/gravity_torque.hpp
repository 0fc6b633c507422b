#pragma once
/// \file gravity_torque.hpp
/// The actuator deformation model's load (docs/theory/humanoid.md, "The actuator deformation model"):
/// the gravity torque each leg joint's gear carries, from the controller's own rigid-body model.
///
///  - Weight split (eqs. 5-6): F_L = μ W, F_R = (1 − μ) W with μ the position of the COM between
///    the sole centres along the line joining them, clamped to [0, 1]; in single support the
///    stance foot carries all of it. W = M g is the whole robot's weight. In a dynamic gait the
///    ground force acts at the ZMP, not under the COM; the split can be taken about the reference
///    ZMP instead (`support_loads` takes the point).
///  - Thesis form (eq. 4): τ_g = −Jᵀ F, F = (0, 0, share · W) the foot's share of the weight acting
///    at its sole centre, J the leg's Jacobian of that point (pelvis to foot). It ignores the legs'
///    own links; the swing leg gets nothing.
///  - Full form: τ_g = g_leg(θ) − Jᵀ F_ext, g_leg the leg links' own gravity torque (leg hanging
///    from the pelvis) and F_ext the foot's share of the weight at its centre of pressure; the
///    swing leg gets g_leg alone. The centres of pressure put the total ground force under the
///    COM: each foot's is its sole centre moved by the part of the COM's offset the split does
///    not explain (zero in double support with the COM between the feet, the COM itself in single
///    support), clamped into the sole.
///
/// Sign: the torque the joint's gear must supply, so that the gear deflects by θ_m − θ_l = τ_g / k
/// (eqs. 2-3). The waist (vertical axis) carries none.
#include <array>
#include <string_view>

#include "flexgait/core/enum_names.hpp"
#include "flexgait/robot/joints.hpp"
#include "flexgait/walking/robot_model.hpp"
#include "flexgait/walking/robot_model_dynamics.hpp"

namespace flexgait::compensation {

enum class GravityForm { kThesis, kFull };
constexpr std::array<EnumName<GravityForm>, 2> enum_names(GravityForm) {
  return {{{GravityForm::kThesis, "thesis"}, {GravityForm::kFull, "full"}}};
}

/// μ of eqs. 5-6: the share of the weight on the left foot, from a point's ground projection (the
/// COM in the thesis) and the sole centres (world xy) [-], clamped to [0, 1]; 0.5 when the soles
/// coincide.
double weight_split(const Eigen::Vector2d& point, const Eigen::Vector2d& left, const Eigen::Vector2d& right);

/// The vertical ground force on each foot as a share of the weight, and where it acts.
struct FootLoads {
  std::array<double, 2> share{};  ///< [-], summing to 1
  /// centre of pressure in each sole's frame (x forward, y left) [m]
  std::array<Eigen::Vector2d, 2> cop{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
};

/// Eqs. 5-6 about `point` (world xy): in double support μ from the point between the sole centres,
/// in single support everything on the stance foot. The centres of pressure put the total force
/// under `point`: each sole centre moved by the part of the point's offset that the split does not
/// explain, clamped into its sole polygon (the nearest point of it, walking::nearest_point) [m].
FootLoads support_loads(const Eigen::Vector2d& point, const std::array<walking::Pose, 2>& soles,
                        const std::array<bool, 2>& swinging, const std::array<walking::SolePolygon, 2>& sole_polygon);

/// The thesis's split (eq. 5): about the model's COM in the pose in `data` (after
/// walking::forward_kinematics), between its soles.
FootLoads com_loads(const walking::RobotModel& model, const walking::RobotModelData& data,
                    const std::array<bool, 2>& swinging);

/// τ_g of every joint for the pose in `data` (after walking::forward_kinematics) with these loads
/// (the weight W = M g shared as `loads` says; the thesis form puts each at its sole centre) [Nm].
humanoid::JointVector gravity_torque(const walking::RobotModel& model, const walking::RobotModelData& data,
                                     const FootLoads& loads, GravityForm form);

/// G = ∂τ_g/∂θ of leg `side` with the loads held (rows and columns in role order) [Nm/rad], after
/// walking::forward_kinematics. Every load on the leg is a vertical force ψ_l ẑ at a point x_l fixed in a link:
/// each link's weight (ψ = m g, the full form) and the ground's push at the sole centre or the centre of
/// pressure (ψ = −share · W), so τ_i = u_i · (Φ_i × ẑ) with Φ_i = Σ_{l below i} ψ_l (x_l − p_i), u_i, p_i joint
/// i's axis and origin. Turning joint j moves the points below it by u_j × (x − p_j) and turns the axes below
/// it; with s the joint nearer the pelvis and d the farther of i, j (s = d allowed),
///     G_sd = G_ds = (u_d · ẑ)(u_s · Φ_d) − (u_s · u_d)(ẑ · Φ_d),
/// symmetric, as the Hessian of the loads' potential (docs/theory/humanoid.md, "The actuator deformation model").
walking::LegTorqueDerivative gravity_torque_derivative(const walking::RobotModel& model,
                                                       const walking::RobotModelData& data, const FootLoads& loads,
                                                       GravityForm form, int side);

}  // namespace flexgait::compensation
