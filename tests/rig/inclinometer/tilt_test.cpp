// Tilt from gravity: axis tilts, the module's tilt and orientation, the mounting correction, the
// averaged measurement with its scatter and motion rejection, and the flip's zero offset.
#include "rig/inclinometer/tilt.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "rig/inclinometer/inclinometer_registry.h"
#include "rig/inclinometer/scripted_inclinometer.h"
#include "sun/incidence_angle.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

using testing::kExactDeg;
using testing::noisySamples;
using testing::ScriptedInclinometer;

TEST(Tilt, AxisTiltsOfKnownVectors) {
  EXPECT_NEAR(axisTilt({0, std::sin(radians(30)), std::cos(radians(30)), {}}).x_deg, 30, kExactDeg);
  EXPECT_NEAR(axisTilt({0, std::sin(radians(30)), std::cos(radians(30)), {}}).y_deg, 0, kExactDeg);
  EXPECT_NEAR(axisTilt({-std::sin(radians(20)), 0, std::cos(radians(20)), {}}).y_deg, 20,
              kExactDeg);
  // Scale does not matter: the tilt is a direction.
  EXPECT_NEAR(axisTilt({0, 0.5, 0.5, {}}).x_deg, 45, kExactDeg);
}

TEST(Tilt, ModuleTiltIsTheNormalsAngleFromVertical) {
  EXPECT_NEAR(moduleTiltDeg({30, 0}), 30, kExactDeg);
  EXPECT_NEAR(moduleTiltDeg({0, -25}), 25, kExactDeg);
  EXPECT_NEAR(moduleTiltDeg({30, 40}),
              degrees(std::acos(std::cos(radians(30)) * std::cos(radians(40)))), kExactDeg);
  // From the vector directly: acos(z / |g|).
  const AccelerationSample g = mountedGravity({30, 40}, {});
  EXPECT_NEAR(moduleTiltDeg(axisTilt(g)), degrees(std::acos(g.z_g)), kExactDeg);
}

TEST(Tilt, MountingCorrectionUndoesTheMountingRotation) {
  const AxisTilt offset{0.7, -0.4};
  for (const AxisTilt tilt : {AxisTilt{30, 0}, AxisTilt{-60, 5}, AxisTilt{10, 80}}) {
    const AccelerationSample read = mountedGravity(tilt, offset);
    const AxisTilt corrected = correctedTilt(read, {offset, 0, ""});
    EXPECT_NEAR(corrected.x_deg, tilt.x_deg, kExactDeg);
    EXPECT_NEAR(corrected.y_deg, tilt.y_deg, kExactDeg);
  }
  // A level surface reads the offset itself.
  const AxisTilt level = axisTilt(mountedGravity({0, 0}, offset));
  EXPECT_NEAR(level.x_deg, offset.x_deg, kExactDeg);
  EXPECT_NEAR(level.y_deg, offset.y_deg, kExactDeg);
}

using Vec3 = std::array<double, 3>;  // east, north, up

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Vec3 direction(double elevation_deg, double azimuth_deg) {
  return {std::cos(radians(elevation_deg)) * std::sin(radians(azimuth_deg)),
          std::cos(radians(elevation_deg)) * std::cos(radians(azimuth_deg)),
          std::sin(radians(elevation_deg))};
}

// Any attitude, built in the world: a normal, and an edge (sensor x) turned `edge_turn_deg` about
// it from the horizontal. The facing azimuth is by definition 90° clockwise from the edge's
// heading; the sensor reads "up" in its own axes. moduleOrientation() must find the normal again.
TEST(ModuleOrientation, RecoversTheNormalOfAnyAttitude) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> elevation(-30, 89), azimuth(0, 360), turn(-40, 40);
  for (int i = 0; i < 1000; ++i) {
    const double normal_elevation = elevation(random), normal_azimuth = azimuth(random);
    const Vec3 z = direction(normal_elevation, normal_azimuth);
    const Vec3 level_edge = direction(0, normal_azimuth - 90);  // horizontal, ⟂ z
    const Vec3 z_cross_edge = cross(z, level_edge);
    const double t = radians(turn(random));
    const Vec3 x{std::cos(t) * level_edge[0] + std::sin(t) * z_cross_edge[0],
                 std::cos(t) * level_edge[1] + std::sin(t) * z_cross_edge[1],
                 std::cos(t) * level_edge[2] + std::sin(t) * z_cross_edge[2]};
    const Vec3 y = cross(z, x);
    const double facing = std::fmod(degrees(std::atan2(x[0], x[1])) + 90 + 360, 360);
    const AccelerationSample up{x[2], y[2], z[2], {}};
    const sun::ModuleOrientation module = moduleOrientation(axisTilt(up), facing);
    // Round trips through atan2/acos in doubles: 1e-9° is rounding.
    EXPECT_NEAR(module.tilt_deg, 90 - normal_elevation, 1e-9);
    EXPECT_NEAR(std::remainder(module.azimuth_deg - normal_azimuth, 360.0), 0, 1e-9)
        << "normal " << normal_elevation << "/" << normal_azimuth << " turn " << degrees(t);
  }
}

TEST(ModuleOrientation, AModuleThatIsNotRolledFacesItsConfiguredAzimuth) {
  for (const double tilt : {0.5, 30.0, 89.0, 90.0, 120.0}) {
    const sun::ModuleOrientation module = moduleOrientation({tilt, 0}, 200);
    EXPECT_NEAR(module.tilt_deg, tilt, kExactDeg);
    EXPECT_NEAR(module.azimuth_deg, 200, 1e-9);
  }
  EXPECT_EQ(moduleOrientation({0, 0}, 123).azimuth_deg, 123);  // flat: the normal has no azimuth
}

// The facing azimuth is where the module faces, whichever way round the sensor is mounted: y down
// the slope reads a negative tilt x for the same module.
TEST(ModuleOrientation, ASensorMountedTheOtherWayRoundFacesTheSameWay) {
  for (const double facing : {0.0, 123.0, 200.0, 359.0}) {
    const sun::ModuleOrientation up_slope = moduleOrientation({30, 5}, facing);
    const sun::ModuleOrientation down_slope = moduleOrientation({-30, -5}, facing);
    EXPECT_NEAR(down_slope.tilt_deg, up_slope.tilt_deg, 1e-9);
    EXPECT_NEAR(std::remainder(down_slope.azimuth_deg - up_slope.azimuth_deg, 360.0), 0, 1e-9);
    EXPECT_LT(std::abs(std::remainder(up_slope.azimuth_deg - facing, 360.0)), 90);
  }
  EXPECT_NEAR(moduleOrientation({-30, 0}, 200).azimuth_deg, 200, 1e-9);
  EXPECT_NEAR(moduleOrientation({30, 0}, 0).azimuth_deg, 0, 1e-9);  // not 359.99999999
  EXPECT_NEAR(moduleOrientation({30, 0}, 359.9999999999).azimuth_deg, 0, 1e-9);
}

TEST(ModuleOrientation, ARolledModuleTurnsItsNormalSideways) {
  // Lamp on the normal of a module tilted 60° facing south; rolled 10° about its up-slope axis
  // (the edge no longer level), the normal swings 10° off the lamp: α = 10°.
  const Vec3 z = direction(30, 180);
  const Vec3 level_edge = direction(0, 90);
  const Vec3 y = cross(z, level_edge);
  const double roll = radians(10);
  const Vec3 z_rolled{std::cos(roll) * z[0] + std::sin(roll) * level_edge[0],
                      std::cos(roll) * z[1] + std::sin(roll) * level_edge[1],
                      std::cos(roll) * z[2] + std::sin(roll) * level_edge[2]};
  const Vec3 x_rolled = cross(y, z_rolled);
  const double facing = std::fmod(degrees(std::atan2(x_rolled[0], x_rolled[1])) + 90 + 360, 360);
  const AxisTilt read = axisTilt({x_rolled[2], y[2], z_rolled[2], {}});
  EXPECT_GT(std::abs(read.y_deg), 4);  // the sensor sees the roll
  EXPECT_NEAR(sun::incidenceAngleDeg(moduleOrientation(read, facing), {30, 180}), 10, 1e-9);
}

TEST(MeasureTilt, AveragesAndReportsTheScatter) {
  // 60 µg per axis at tilt 30: the ADXL355's noise at the driver's data rate.
  ScriptedInclinometer sensor(noisySamples({30, 0}, 400, 60e-6));
  TiltOptions options;
  options.samples = 400;
  const auto reading = measureTilt(sensor, options);
  ASSERT_TRUE(reading) << reading.error().message;
  // σ ≈ 60 µg ≈ 0.0034° per sample; the mean of 400 is ±0.00017°: 0.001° is 6σ.
  EXPECT_NEAR(reading->module_tilt_deg, 30, 1e-3);
  EXPECT_NEAR(reading->tilt_std_deg, degrees(60e-6), degrees(60e-6) * 0.2);  // ±20 %: 400 samples
  EXPECT_NEAR(reading->tilt_uncertainty_deg, reading->tilt_std_deg / 20, 1e-12);
  EXPECT_EQ(reading->samples, 400);
  ASSERT_TRUE(reading->mean.temperature_c);
  EXPECT_DOUBLE_EQ(*reading->mean.temperature_c, 24.0);
}

TEST(MeasureTilt, RejectsAMovingRig) {
  ScriptedInclinometer sensor(noisySamples({30, 0}, 50, 0.01));  // 0.6° of scatter
  const auto reading = measureTilt(sensor, {});
  ASSERT_FALSE(reading);
  EXPECT_NE(reading.error().message.find("the rig is moving"), std::string::npos)
      << reading.error().message;
  EXPECT_NE(reading.error().message.find("test:scripted"), std::string::npos);
}

TEST(MeasureTilt, RejectsASampleThatIsNotGravity) {
  auto samples = noisySamples({30, 0}, 50, 0);
  samples[10] = AccelerationSample{0, 0, 1.5, {}};
  ScriptedInclinometer sensor(std::move(samples));
  const auto reading = measureTilt(sensor, {});
  ASSERT_FALSE(reading);
  EXPECT_NE(reading.error().message.find("sample 11 measures 1.500 g"), std::string::npos)
      << reading.error().message;
}

TEST(MeasureTilt, PassesOnTheSensorsError) {
  auto samples = noisySamples({30, 0}, 50, 0);
  samples.at(3) = hardwareError("adxl355:/dev/i2c-1@0x1d: saturated");
  ScriptedInclinometer sensor(std::move(samples));
  const auto reading = measureTilt(sensor, {});
  ASSERT_FALSE(reading);
  EXPECT_EQ(reading.error().message, "adxl355:/dev/i2c-1@0x1d: saturated");
}

TEST(MeasureTilt, ValidatesItsOptions) {
  ScriptedInclinometer sensor({});
  TiltOptions options;
  options.samples = 1;
  EXPECT_EQ(measureTilt(sensor, options).error().code, ErrorCode::kBadInput);
  options = {};
  options.max_tilt_std_deg = 0;
  EXPECT_EQ(measureTilt(sensor, options).error().code, ErrorCode::kBadInput);
}

// The same module at 87°, the sensor turned 90° about its normal: the scatter (angles to the mean
// direction) does not depend on the turn, as axis tilts near ±90° would.
TEST(MeasureTilt, ScatterDoesNotDependOnTheSensorsTurn) {
  auto upright = openInclinometer("sim:87,seed=3");
  auto turned = openInclinometer("sim:0,roll_deg=87,seed=3");
  ASSERT_TRUE(upright && turned);
  const auto a = measureTilt(**upright, {});
  const auto b = measureTilt(**turned, {});
  ASSERT_TRUE(a) << a.error().message;
  ASSERT_TRUE(b) << b.error().message;
  EXPECT_NEAR(a->module_tilt_deg, 87, 0.002);  // 60 µg noise, 50 samples: ±0.0005°
  EXPECT_NEAR(b->module_tilt_deg, 87, 0.002);
  // Both are the simulator's 60 µg ≈ 0.0034°; 50 samples estimate a σ to ±10 % (1σ): ±30 %.
  EXPECT_NEAR(a->tilt_std_deg, degrees(60e-6), 0.3 * degrees(60e-6));
  EXPECT_NEAR(b->tilt_std_deg, degrees(60e-6), 0.3 * degrees(60e-6));
}

TEST(FlipCalibration, RecoversTheMountingOffset) {
  const AxisTilt offset{0.3, -0.2};
  // On one axis, rotations about the same axis add exactly: the half-sum is the offset exactly.
  ScriptedInclinometer first(noisySamples({5, 0}, 50, 0, {0.3, 0}));
  ScriptedInclinometer second(noisySamples({-5, 0}, 50, 0, {0.3, 0}));
  const auto zero = flipZeroOffset(*measureTilt(first, {}), *measureTilt(second, {}));
  EXPECT_NEAR(zero.offset.x_deg, 0.3, kExactDeg);
  EXPECT_NEAR(zero.offset.y_deg, 0.0, kExactDeg);

  // Both axes tilted, a surface 9° × 9° off level: the bisector of the two up directions is
  // exact at any surface tilt (the half-sum of axis tilts would be 0.01° off here). Noise-free
  // samples: 1e-9° is rounding.
  ScriptedInclinometer a(noisySamples({9, 9}, 50, 0, offset));
  ScriptedInclinometer b(noisySamples({-9, -9}, 50, 0, offset));
  const auto both = flipZeroOffset(*measureTilt(a, {}), *measureTilt(b, {}));
  EXPECT_NEAR(both.offset.x_deg, offset.x_deg, 1e-9);
  EXPECT_NEAR(both.offset.y_deg, offset.y_deg, 1e-9);

  // After correction, a module tilted 30° reads 30°.
  ScriptedInclinometer tilted(noisySamples({30, 0}, 50, 0, offset));
  const auto reading = measureTilt(tilted, {}, both);
  EXPECT_NEAR(reading->module_tilt_deg, 30, 1e-9);
  // Uncorrected it is off by about the offset.
  ScriptedInclinometer raw(noisySamples({30, 0}, 50, 0, offset));
  EXPECT_GT(std::abs(measureTilt(raw, {})->module_tilt_deg - 30), 0.2);
}

TEST(FlipCalibration, UncertaintyIsTheHalfSumOfTheMeansUncertainties) {
  TiltReading a, b;
  a.tilt_std_deg = 0.004;
  b.tilt_std_deg = 0.003;
  a.samples = b.samples = 100;
  const auto zero = flipZeroOffset(a, b);
  EXPECT_NEAR(zero.uncertainty_deg, std::hypot(0.0004, 0.0003) / 2, 1e-15);
}

}  // namespace
}  // namespace glarecam::rig
