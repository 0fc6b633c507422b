#pragma once
/// \file landing_adaptation.hpp
/// Landing orientation control (Kim, Park & Oh 2007, KHR-2's "landing orientation controller";
/// docs/guide/campaigns.md, the rough floor). A rigid sole commanded level on a bumpy floor rests on one bump or
/// one edge: its centre of pressure is pinned there and the balance loop loses the foot. For a
/// window after each touchdown — a foot that swung and lands; not the stance the robot starts in,
/// where the torques are the twin settling onto its soles (adapted to them and held, the dcm twin
/// standing with step adjustment on flat ground rocked heel to toe and fell at 2.4 s) — the sole's
/// commanded roll and pitch follow the ground's torque about its centre like a limp ankle,
///
///   δ̇ = A τ,   |δ_x|, |δ_y| ≤ δ_max,                                         (L1)
///
/// so the sole rocks onto the floor until its load is spread around its centre (three or more
/// contacts, the centre inside them). After the window δ is held for the rest of the stance: the
/// other balance terms (foot torque compliance, DCM admittance) act about the adapted sole. While
/// the foot swings δ returns to level, δ̇ = −δ / T_r (the swing foot lands level, blind).
/// A = 0 switches it off (δ ≡ 0). The controller only feels the floor through its F/T sensors.
#include <Eigen/Dense>

#include <array>
#include <limits>

namespace flexgait::walking {

struct LandingGains {
  double admittance = 0;     ///< A [rad/(N m s)]; 0: off
  double window = 0.1;       ///< how long after touchdown δ follows τ [s]
  double limit = 0.15;       ///< δ_max per axis [rad]
  double return_time = 0.1;  ///< T_r, while swinging [s]
};

/// The adapted sole tilts of both feet (no allocation; one value per controller).
class LandingAdaptation {
 public:
  explicit LandingAdaptation(const LandingGains& gains) : gains_(gains) {}
  /// One control period of foot `side`.
  /// \param t time [s]; \param period control period [s]
  /// \param swinging the plan swings the foot; \param contact the foot is loaded (F/T)
  /// \param torque ground torque about the sole centre, sole x and y [Nm] (as FootContact)
  /// \param live the F/T readings are good (else δ is held)
  void update(int side, double t, double period, bool swinging, bool contact, const Eigen::Vector2d& torque, bool live);
  /// δ of foot `side`: roll (about sole x), pitch (about sole y) [rad].
  const Eigen::Vector2d& tilt(int side) const { return tilt_[side]; }

 private:
  LandingGains gains_;
  std::array<Eigen::Vector2d, 2> tilt_{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  std::array<bool, 2> landed_{true, true};  ///< touched down since the last swing (standing at the start)
  std::array<double, 2> touchdown_{-std::numeric_limits<double>::infinity(),
                                   -std::numeric_limits<double>::infinity()};  ///< when [s]
};

}  // namespace flexgait::walking
