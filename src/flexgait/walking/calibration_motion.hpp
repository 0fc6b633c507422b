#pragma once
/// \file calibration_motion.hpp
/// A stiffness calibration in the start stance (docs/guide/compensation.md, control.k_estimation = calibrate): both
/// soles
/// stay flat on the floor while the body moves slowly, so every leg joint's gear torque changes in its
/// own way (compensation/chain_stiffness_calibration.hpp identifies each joint's k from it).
///
/// Walking does not separate the leg's parallel joints: their torques rise and fall together
/// (docs/guide/compensation.md). Each component below moves a different combination:
/// - the COM sideways (the ZMP reference): the weight moves between the legs, so the left and right
///   legs' torques differ;
/// - the COM forward and back: the ankle pitch and the knee (not the hip, whose upper body is carried
///   upright);
/// - a squat (the pelvis lowered): the knee above all;
/// - the pelvis pitched: the hip pitch (the upper body's weight ahead of or behind the hip);
/// - each sole's commanded roll: the foot presses on one edge, the ankle and hip roll of that leg.
/// Each at its own period (ratios 1 : 1.4 : 2.2 : 2.6 of calibration.period, the soles' rolls 0.633
/// and 0.543), so no two move in step. The whole is faded in and out over calibration.ramp
/// by sin², so it starts and ends at rest.
///
/// The soles' rolls excite the weakest joints (the ankle rolls), so their frequencies keep clear of
/// what the other components make through the plant's nonlinearity (the contact, the weight split
/// times the lever): at 1.58 and 1.84 of the sideways frequency ω, each is at least 0.12 ω from every
/// sum and difference of two of the others' frequencies (ω, ω/1.4, ω/2.2, ω/2.6 and the other sole's)
/// and from their doubles. The first design (0.74 and 0.86: 1.35 ω and 1.16 ω) had the right sole
/// 0.006 ω from ω/1.4 + ω/2.2; the 90 s window resolves about 0.06 ω, so a by-product of the forward
/// motion and the squat read as the right ankle roll.
#include "flexgait/core/record.hpp"

namespace flexgait::walking {

struct CalibrationMotion {
  double time = 0.0;          ///< duration, fades included; 0: no calibration [s]
  double start = 1.0;         ///< when it begins [s]
  double period = 5.0;        ///< period of the COM's sideways motion (the others in fixed ratios) [s]
  double ramp = 3.0;          ///< fade in and fade out [s]
  double com_y = 0.07;        ///< sideways COM (ZMP reference) amplitude [m]
  double com_x = 0.03;        ///< forward COM amplitude [m]
  double squat = 0.04;        ///< deepest lowering of the pelvis [m]
  double pelvis_pitch = 0.1;  ///< pelvis pitch amplitude [rad]
  double sole_roll = 0.01;    ///< each sole's commanded roll amplitude [rad]

  // Each component's period over calibration.period (the squat's is that of its sin², a full dip).
  static constexpr double kForwardRatio = 1.4;          ///< the COM forward and back
  static constexpr double kSquatRatio = 2.2;            ///< the squat
  static constexpr double kPelvisPitchRatio = 2.6;      ///< the pelvis pitch
  static constexpr double kLeftSoleRollRatio = 0.633;   ///< left sole roll's period over calibration.period
  static constexpr double kRightSoleRollRatio = 0.543;  ///< right sole roll's period over calibration.period

  double end() const { return time > 0 ? start + time : 0.0; }  ///< [s]

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("calibration.time", s.time,
      {.unit = "s",
       .doc = "stiffness calibration in the start stance: its duration (0 = none; walk.start_time must "
              "leave walk.preview_time after it)",
       .bounds = closed(0, 3600)});
    v("calibration.start", s.start, {.unit = "s", .doc = "calibration: when it begins", .bounds = closed(0, 100)});
    v("calibration.period", s.period,
      {.unit = "s",
       .doc = "calibration: period of the COM's sideways motion (forward 1.4x, squat 2.2x, pelvis pitch 2.6x, "
              "the soles' rolls 0.633x and 0.543x)",
       .bounds = closed(1, 100)});
    v("calibration.ramp", s.ramp,
      {.unit = "s", .doc = "calibration: fade in and fade out", .bounds = closed(0.1, 100)});
    v("calibration.com_y", s.com_y,
      {.unit = "m", .doc = "calibration: sideways COM amplitude", .bounds = closed(0, 0.3)});
    v("calibration.com_x", s.com_x,
      {.unit = "m", .doc = "calibration: forward COM amplitude", .bounds = closed(0, 0.2)});
    v("calibration.squat", s.squat,
      {.unit = "m", .doc = "calibration: deepest lowering of the pelvis", .bounds = closed(0, 0.2)});
    v("calibration.pelvis_pitch", s.pelvis_pitch,
      {.unit = "rad", .doc = "calibration: pelvis pitch amplitude", .bounds = closed(0, 0.3)});
    v("calibration.sole_roll", s.sole_roll,
      {.unit = "rad",
       .doc = "calibration: each sole's commanded roll amplitude (the foot presses on an edge)",
       .bounds = closed(0, 0.02)});
  }
};

/// The calibration's offsets on the standing pose at time t (all zero outside it).
struct CalibrationOffset {
  double com_x = 0, com_y = 0;   ///< on the ZMP reference [m]
  double pelvis_z = 0;           ///< on the pelvis height (≤ 0) [m]
  double pelvis_pitch = 0;       ///< on the pelvis pitch command [rad]
  double sole_roll[2] = {0, 0};  ///< on the left, right sole's commanded roll [rad]
};

CalibrationOffset calibration_offset(const CalibrationMotion& m, double t);

}  // namespace flexgait::walking
