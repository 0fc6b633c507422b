// The tilt observer (tilt_observer.hpp (T1)–(T3)) on exact synthetic motion: an IMU at the end of a
// rigid rod of length L swinging about a fixed ground anchor (a foot flat on the ground) in roll
// and pitch. The measurements are exact, so the observer's error is its own: from the truth it
// stays within the Euler scheme's O(dt) (dt = 1 ms), and from a 0.3 rad error it converges.
#include "flexgait/walking/tilt_observer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "flexgait/walking/rotation.hpp"

namespace flexgait::walking {
namespace {

constexpr double kG = 9.81, kL = 0.7, kDt = 1e-3;

struct Swing {  // roll = a sin(Ω t), pitch = b sin(1.3 Ω t + 0.4)
  double a = 0.15, b = 0.2, w = 3.0;
  Eigen::Vector2d angles(double t) const { return {a * std::sin(w * t), b * std::sin(1.3 * w * t + 0.4)}; }
  Matrix3d R(double t) const {
    const Eigen::Vector2d q = angles(t);
    return rot_y(q(1)) * rot_x(q(0));
  }
  Vector3d p(double t) const { return R(t) * Vector3d(0, 0, kL); }  // the IMU, the anchor at the origin
};

// Body rate ω (Rᵀ Ṙ = [ω]×), velocity and acceleration by central differences of the exact motion
// (h = 1e-5 s: truncation ~1e-10, rounding ~1e-11 on these O(1) quantities).
struct Sample {
  Vector3d omega, y_v, y_a, tilt;
};
Sample sample(const Swing& s, double t) {
  constexpr double h = 1e-5;
  const Matrix3d R = s.R(t), Rd = (s.R(t + h) - s.R(t - h)) / (2 * h);
  const Matrix3d W = R.transpose() * Rd;
  const Vector3d omega(W(2, 1), W(0, 2), W(1, 0));
  const Vector3d pdd = (s.p(t + h) - 2 * s.p(t) + s.p(t - h)) / (h * h);
  const Vector3d anchor = R.transpose() * (Vector3d::Zero() - s.p(t));  // constant: (0, 0, −L)
  return {omega, -omega.cross(anchor), R.transpose() * (pdd + kG * Vector3d::UnitZ()),
          R.transpose() * Vector3d::UnitZ()};
}

TEST(TiltObserver, StaysOnTheTruthAndConvergesToItFromAWrongTilt) {
  const Swing swing;
  for (const double initial_error : {0.0, 0.3}) {
    TiltObserver obs(TiltObserverGains{50, 5, 15, kG});
    const Sample s0 = sample(swing, 0);
    obs.reset(s0.y_v, rot_x(initial_error) * s0.tilt);
    double late = 0;
    for (int k = 1; k <= 20000; ++k) {  // 20 s
      const double t = k * kDt;
      const Sample s = sample(swing, t);
      obs.update(s.y_v, s.y_a, s.omega, kDt);
      const double err = std::acos(std::clamp(obs.tilt().dot(s.tilt), -1.0, 1.0));
      if (t > 15) late = std::max(late, err);
      if (initial_error == 0) {
        EXPECT_LT(err, 5e-3) << "t = " << t;
      }
    }
    EXPECT_LT(late, 5e-3) << "from " << initial_error;
  }
}

TEST(TiltObserver, TheTiltGivesRollAndPitch) {
  for (const double roll : {-0.3, 0.0, 0.2}) {
    for (const double pitch : {-0.4, 0.1}) {
      const Eigen::Vector2d rp = roll_pitch_of_tilt(rpy_to_matrix(roll, pitch, 0.7).transpose() * Vector3d::UnitZ());
      EXPECT_NEAR(rp(0), roll, 1e-15);
      EXPECT_NEAR(rp(1), pitch, 1e-15);
    }
  }
}

}  // namespace
}  // namespace flexgait::walking
