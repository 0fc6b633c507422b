// The wheel's parameter records and their cross-field checks (rimless/parameters.hpp): the schema
// holds every record's keys once, with the struct defaults; validate() refuses μ_k > μ_s, Stribeck
// keys under Coulomb friction and |initial.beta| >= π/N, each naming its key.
#include "flexgait/rimless/parameters.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <string>

namespace flexgait::rimless {
namespace {

std::string refused_key(const WheelParams& w, const InitialState& s) {
  try {
    validate(w, s);
  } catch (const ConfigError& e) {
    return e.key();
  }
  return "";
}

TEST(Parameters, SchemaHoldsTheRecordsWithTheirDefaults) {
  const Schema schema = rimless_schema();
  for (const char* key : {"rimless.m", "rimless.friction", "initial.omega", "initial.beta", "sim.steps"})
    EXPECT_NE(schema.find(key), nullptr) << key;
  // resolve_config with no file and no --set gives the structs' defaults back.
  const Config c = resolve_config(schema, std::nullopt, {});
  const WheelParams w = wheel_from_config(c);
  const WheelParams d;
  EXPECT_EQ(w.K, d.K);
  EXPECT_EQ(w.legs, d.legs);
  EXPECT_EQ(w.friction, d.friction);
  EXPECT_EQ(initial_from_config(c).omega, InitialState{}.omega);
  EXPECT_EQ(simulation_from_config(c).steps, SimulationOptions{}.steps);
}

TEST(Parameters, DefaultsAreValid) {
  EXPECT_EQ(refused_key(WheelParams{}, InitialState{}), "");
}

TEST(Parameters, KineticAboveStaticFrictionIsRefused) {
  WheelParams w;
  w.mu_s = 0.3;
  w.mu_k = 0.3;
  EXPECT_EQ(refused_key(w, {}), "");  // equal is allowed
  w.mu_k = 0.31;
  EXPECT_EQ(refused_key(w, {}), "rimless.mu_k");
}

TEST(Parameters, StribeckKeysApplyOnlyWithStribeckFriction) {
  for (const char* key : {"rimless.stribeck_velocity", "rimless.stribeck_exponent", "rimless.viscous"}) {
    WheelParams w;
    const std::string k = key;
    if (k == "rimless.stribeck_velocity") w.stribeck_velocity = 0.2;
    if (k == "rimless.stribeck_exponent") w.stribeck_exponent = 1.0;
    if (k == "rimless.viscous") w.viscous = 0.1;
    EXPECT_EQ(refused_key(w, {}), k);
    w.friction = Friction::Stribeck;
    EXPECT_EQ(refused_key(w, {}), "") << k;
  }
}

// Scales that overflow (an impact of infinite momentum, formerly an internal error) or vanish are
// refused naming the most extreme of m, L0, I, K, C, g; extreme but representable ones are not.
TEST(Parameters, WheelScalesMustBeFiniteAndPositive) {
  WheelParams w;
  w.L0 = 1e300;
  EXPECT_EQ(refused_key(w, InitialState{}), "rimless.L0");
  w = WheelParams{};
  w.m = 1e308;
  w.C = 1e200;
  EXPECT_EQ(refused_key(w, InitialState{}), "rimless.m");  // m g L0 = 9.81e308 overflows; m the most extreme
  w = WheelParams{};
  w.m = 1e-320;
  w.I = 0;
  w.L0 = 1e-10;
  EXPECT_EQ(refused_key(w, InitialState{}), "rimless.m");  // m L0² + I = 0
  w = WheelParams{};
  w.K = 1e300;  // K L0² = 1e300: finite
  EXPECT_EQ(refused_key(w, InitialState{}), "");
}

TEST(Parameters, InitialBetaMustLieWithinHalfTheSpokeAngle) {
  WheelParams w;
  w.legs = 6;  // α = π/6
  InitialState s;
  s.beta = std::nextafter(std::numbers::pi / 6, 0.0);
  EXPECT_EQ(refused_key(w, s), "");
  s.beta = -std::numbers::pi / 6;
  EXPECT_EQ(refused_key(w, s), "initial.beta");
}

}  // namespace
}  // namespace flexgait::rimless
