// Leg kinematics helpers against their definitions.
#include "flexgait/rimless/contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>

namespace flexgait::rimless {
namespace {

std::uint64_t bits(double v) {
  std::uint64_t b = 0;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// leg_angle computes remainder(θ + 2αk, 2π) by one fused multiply-add where that is exact: it
// must give libm's remainder bit for bit (the simulations' bytes depend on it), also where the
// quotient is a half-integer to within round-off (there it hands over to libm).
TEST(LegAngle, IsLibmRemainderBitForBit) {
  constexpr double P = 2.0 * std::numbers::pi;
  for (int legs : {3, 10, 37}) {
    WheelParams w;
    w.legs = legs;
    auto expect_same = [&](double theta, int k) {
      const double x = theta + 2.0 * w.alpha() * k;
      ASSERT_EQ(bits(leg_angle(w, k, theta)), bits(std::remainder(x, P))) << "theta " << theta << " leg " << k;
    };
    std::mt19937_64 rng(legs);
    std::uniform_real_distribution<double> wide(-1e4, 1e4), narrow(-10.0, 10.0);
    for (int i = 0; i < 20000; ++i) {
      const int k = static_cast<int>(rng() % static_cast<unsigned>(legs));
      expect_same(wide(rng), k);
      expect_same(narrow(rng), k);
    }
    // Quotients at half-integers, and a few ulps either side.
    for (int n = -50; n <= 50; ++n) {
      const double half = (n + 0.5) * P;
      for (double x = std::nextafter(std::nextafter(half, -1e9), -1e9);
           x <= std::nextafter(std::nextafter(half, 1e9), 1e9); x = std::nextafter(x, 1e9))
        expect_same(x, 0);
      expect_same(n * P, 0);  // exact multiples: remainder 0
    }
  }
}

// AngleWrap removes the turns it kept from the last call by two subtractions: it must give
// wrap_angle's number bit for bit along a slowly moving angle (a foot's leg angle over a run's
// right-hand sides: its cached turns right) and wherever the angle jumps (a new turn, another
// leg in the slot: the cache wrong), also at half-integer quotients and exact multiples.
TEST(AngleWrap, IsWrapAngleBitForBit) {
  constexpr double P = 2.0 * std::numbers::pi;
  AngleWrap wrap;
  const auto expect_same = [&](double x) { ASSERT_EQ(bits(wrap(x)), bits(wrap_angle(x))) << "x " << x; };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> step(-0.05, 0.05), jump(-1e4, 1e4);
  double x = 0.0;
  for (int i = 0; i < 200000; ++i) {  // about 300 turns each way, a jump now and then
    x = i % 1000 == 999 ? jump(rng) : x + step(rng) - (i < 100000 ? 0.02 : -0.02);
    expect_same(x);
  }
  for (int n = -50; n <= 50; ++n) {
    const double half = (n + 0.5) * P;
    for (double v = std::nextafter(std::nextafter(half, -1e9), -1e9);
         v <= std::nextafter(std::nextafter(half, 1e9), 1e9); v = std::nextafter(v, 1e9))
      expect_same(v);
    expect_same(n * P);
    expect_same(n * P + 2.999999);  // the edge of the kept turns' margin, both sides
    expect_same(n * P - 3.000001);
  }
  expect_same(0.0);
  expect_same(-0.0);
  expect_same(1e300);  // a huge angle: no turns kept
  expect_same(0.5);
}

}  // namespace
}  // namespace flexgait::rimless
