#pragma once
/// \file calibration_motion.hpp
/// A stiffness calibration in the start stance (issue 20, control.k_estimation = calibrate): both soles
/// stay flat on the floor while the body moves slowly, so every leg joint's gear torque changes in its
/// own way (compensation/chain_stiffness_calibration.hpp identifies each joint's k from it).
///
/// Walking does not separate the leg's parallel joints: their torques rise and fall together
/// (README, "per-joint"). Each component below moves a different combination:
/// - the COM sideways (the ZMP reference): the weight moves between the legs, so the left and right
///   legs' torques differ;
/// - the COM forward and back: the ankle pitch and the knee (not the hip, whose upper body is carried
///   upright);
/// - a squat (the pelvis lowered): the knee above all;
/// - the pelvis pitched: the hip pitch (the upper body's weight ahead of or behind the hip);
/// - each sole's commanded roll: the foot presses on one edge, the ankle and hip roll of that leg.
/// Each at its own period (ratios 1 : 1.4 : 2.2 : 2.6 of calibration.period, the soles' rolls 0.74
/// and 0.86), so no two move in step. The whole is faded in and out over calibration.ramp
/// by sin², so it starts and ends at rest.
#include "flexgait/core/record.hpp"

namespace flexgait::walking {

struct CalibrationMotion {
  double time = 0.0;        ///< duration, fades included; 0: no calibration [s]
  double start = 1.0;       ///< when it begins [s]
  double period = 5.0;      ///< period of the COM's sideways motion (the others in fixed ratios) [s]
  double ramp = 3.0;        ///< fade in and fade out [s]
  double com_y = 0.07;      ///< sideways COM (ZMP reference) amplitude [m]
  double com_x = 0.03;      ///< forward COM amplitude [m]
  double squat = 0.04;      ///< deepest lowering of the pelvis [m]
  double pelvis_pitch = 0.1;  ///< pelvis pitch amplitude [rad]
  double sole_roll = 0.003;   ///< each sole's commanded roll amplitude [rad]

  double end() const { return time > 0 ? start + time : 0.0; }  ///< [s]

  template <class Self, class Visit>
  static void visit_fields(Self& s, Visit& v) {
    v("calibration.time", s.time,
      {.unit = "s", .doc = "stiffness calibration in the start stance: its duration (0 = none; walk.start_time must "
                           "leave walk.preview_time after it)",
       .bounds = closed(0, 3600)});
    v("calibration.start", s.start, {.unit = "s", .doc = "calibration: when it begins", .bounds = closed(0, 100)});
    v("calibration.period", s.period,
      {.unit = "s", .doc = "calibration: period of the COM's sideways motion (forward 1.4x, squat 2.2x, pelvis pitch 2.6x, "
                           "the soles' rolls 0.74x and 0.86x)",
       .bounds = closed(1, 100)});
    v("calibration.ramp", s.ramp, {.unit = "s", .doc = "calibration: fade in and fade out", .bounds = closed(0.1, 100)});
    v("calibration.com_y", s.com_y, {.unit = "m", .doc = "calibration: sideways COM amplitude", .bounds = closed(0, 0.3)});
    v("calibration.com_x", s.com_x, {.unit = "m", .doc = "calibration: forward COM amplitude", .bounds = closed(0, 0.2)});
    v("calibration.squat", s.squat, {.unit = "m", .doc = "calibration: deepest lowering of the pelvis", .bounds = closed(0, 0.2)});
    v("calibration.pelvis_pitch", s.pelvis_pitch,
      {.unit = "rad", .doc = "calibration: pelvis pitch amplitude", .bounds = closed(0, 0.3)});
    v("calibration.sole_roll", s.sole_roll,
      {.unit = "rad", .doc = "calibration: each sole's commanded roll amplitude (the foot presses on an edge)",
       .bounds = closed(0, 0.02)});
  }
};

/// The calibration's offsets on the standing pose at time t (all zero outside it).
struct CalibrationOffset {
  double com_x = 0, com_y = 0;    ///< on the ZMP reference [m]
  double pelvis_z = 0;            ///< on the pelvis height (≤ 0) [m]
  double pelvis_pitch = 0;        ///< on the pelvis pitch command [rad]
  double sole_roll[2] = {0, 0};   ///< on the left, right sole's commanded roll [rad]
};

CalibrationOffset calibration_offset(const CalibrationMotion& m, double t);

}  // namespace flexgait::walking
