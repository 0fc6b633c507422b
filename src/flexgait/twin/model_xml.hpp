#pragma once
/// \file model_xml.hpp
/// The twin as MJCF, written from RobotParams (docs/theory/humanoid.md, "The robot"): a free-floating
/// pelvis, a waist yaw joint to the chest (arms and head rigid on it), two 6-joint legs, box soles.
/// Masses, centres of mass and inertias are THORMANG3's (builtin_inertials.hpp; the shapes are for
/// looks); only the soles collide with the floor, each sole box robot.sole_offset_y outward of its ankle.
/// Each actuated joint carries its gear stiffness and damping (a viewer of the exported file sees
/// the springs; the running twin applies them itself, detail/elastic_drives.hpp). Sites: "imu" at the pelvis origin,
/// "l_ft"/"r_ft" at the ankle axes between the ankle-roll link and the foot (the F/T sensors). Joint angles zero: legs
/// straight.
#include <string>

#include "flexgait/robot/robot_params.hpp"
#include "flexgait/twin/plant_params.hpp"

namespace flexgait::twin {

std::string humanoid_mjcf(const humanoid::RobotParams& robot, const PlantParams& plant);

/// The twin's document around its robot (shared by the builtin and loaded twins): compiler and
/// physics options from `plant`, the floor (plant.terrain, terrain.hpp; friction sole_friction, contact time constant),
/// the robot's `bodies` (MJCF body elements, indented for the worldbody), `contact` (a <contact> element or ""), and
/// the F/T and IMU sensors on the sites l_ft, r_ft and imu. The look that the twin's pictures and the replay scenes'
/// share (renderer.hpp): the <visual> element (offscreen buffer width × height [pixels], a 4096² shadow map, a dim
/// headlight) and the <asset> entries flexgait_sky (a gradient skybox), flexgait_grid and flexgait_floor (the checkered
/// floor: 0.5 m squares, a line every 1 m).
std::string look_visual_mjcf(int width, int height);
std::string look_assets_mjcf();

/// The twin's MJCF document around `bodies`: gravity [m/s^2] along −z (the robot description's), the
/// floor from the plant's terrain with the soles' friction, the contact exclusions `contact`.
std::string twin_document(const std::string& model, bool inertia_from_geom, double sole_friction, double gravity,
                          const PlantParams& plant, const std::string& bodies, const std::string& contact);

}  // namespace flexgait::twin
