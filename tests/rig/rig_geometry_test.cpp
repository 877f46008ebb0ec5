// The rig's geometry: tilt from gravity (axis tilts, mounting correction, averaging, motion
// rejection), the flip calibration, α on constructed geometries, the clock check, the TOML config
// and the calibration file's inclinometer block.
#include "rig/rig_geometry.h"

#include <gtest/gtest.h>
#include <sys/timex.h>

#include <array>
#include <cmath>
#include <deque>
#include <fstream>
#include <numbers>
#include <random>

#include "core/stack_manifest.h"
#include "rig/config_table.h"
#include "rig/inclinometer/inclinometer_registry.h"
#include "rig/inclinometer/tilt.h"
#include "rig/inclinometer/zero_offset_file.h"
#include "rig/rig_config.h"
#include "sun/clock_sync.h"
#include "sun/incidence_angle.h"
#include "sun/utc_time.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

using testing::TempDir;

// Pure trigonometry in doubles: agreement to 1e-9° is rounding, not approximation.
constexpr double kExactDeg = 1e-9;

double deg(double rad) { return rad * 180.0 / std::numbers::pi; }
double rad(double deg) { return deg * std::numbers::pi / 180.0; }

// An inclinometer replaying scripted samples (or an error).
class ScriptedInclinometer final : public Inclinometer {
 public:
  explicit ScriptedInclinometer(std::deque<Result<AccelerationSample>> samples)
      : samples_(std::move(samples)) {}
  const InclinometerInfo& info() const override { return info_; }
  Result<AccelerationSample> read() override {
    if (samples_.empty()) return hardwareError("script exhausted");
    auto next = samples_.front();
    samples_.pop_front();
    return next;
  }

 private:
  InclinometerInfo info_{
      .uri = "test:scripted", .backend = "test", .model = "", .detail = "", .full_scale_g = 2};
  std::deque<Result<AccelerationSample>> samples_;
};

// `n` samples of the attitude `tilt` (no mounting error) with white noise of `noise_g` per axis.
std::deque<Result<AccelerationSample>> noisySamples(AxisTilt tilt, int n, double noise_g,
                                                    AxisTilt offset = {}, unsigned seed = 7) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_g);
  std::deque<Result<AccelerationSample>> samples;
  for (int i = 0; i < n; ++i) {
    AccelerationSample s = mountedGravity(tilt, offset);
    s.x_g += noise(random);
    s.y_g += noise(random);
    s.z_g += noise(random);
    s.temperature_c = 24.0;
    samples.push_back(s);
  }
  return samples;
}

// ------------------------------------------------------------------------------- tilt maths

TEST(Tilt, AxisTiltsOfKnownVectors) {
  EXPECT_NEAR(axisTilt({0, std::sin(rad(30)), std::cos(rad(30)), {}}).x_deg, 30, kExactDeg);
  EXPECT_NEAR(axisTilt({0, std::sin(rad(30)), std::cos(rad(30)), {}}).y_deg, 0, kExactDeg);
  EXPECT_NEAR(axisTilt({-std::sin(rad(20)), 0, std::cos(rad(20)), {}}).y_deg, 20, kExactDeg);
  // Scale does not matter: the tilt is a direction.
  EXPECT_NEAR(axisTilt({0, 0.5, 0.5, {}}).x_deg, 45, kExactDeg);
}

TEST(Tilt, ModuleTiltIsTheNormalsAngleFromVertical) {
  EXPECT_NEAR(moduleTiltDeg({30, 0}), 30, kExactDeg);
  EXPECT_NEAR(moduleTiltDeg({0, -25}), 25, kExactDeg);
  EXPECT_NEAR(moduleTiltDeg({30, 40}), deg(std::acos(std::cos(rad(30)) * std::cos(rad(40)))),
              kExactDeg);
  // From the vector directly: acos(z / |g|).
  const AccelerationSample g = mountedGravity({30, 40}, {});
  EXPECT_NEAR(moduleTiltDeg(axisTilt(g)), deg(std::acos(g.z_g)), kExactDeg);
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
  return {std::cos(rad(elevation_deg)) * std::sin(rad(azimuth_deg)),
          std::cos(rad(elevation_deg)) * std::cos(rad(azimuth_deg)), std::sin(rad(elevation_deg))};
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
    const double t = rad(turn(random));
    const Vec3 x{std::cos(t) * level_edge[0] + std::sin(t) * z_cross_edge[0],
                 std::cos(t) * level_edge[1] + std::sin(t) * z_cross_edge[1],
                 std::cos(t) * level_edge[2] + std::sin(t) * z_cross_edge[2]};
    const Vec3 y = cross(z, x);
    const double facing = std::fmod(deg(std::atan2(x[0], x[1])) + 90 + 360, 360);
    const AccelerationSample up{x[2], y[2], z[2], {}};
    const sun::ModuleOrientation module = moduleOrientation(axisTilt(up), facing);
    // Round trips through atan2/acos in doubles: 1e-9° is rounding.
    EXPECT_NEAR(module.tilt_deg, 90 - normal_elevation, 1e-9);
    EXPECT_NEAR(std::remainder(module.azimuth_deg - normal_azimuth, 360.0), 0, 1e-9)
        << "normal " << normal_elevation << "/" << normal_azimuth << " turn " << deg(t);
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
  const double roll = rad(10);
  const Vec3 z_rolled{std::cos(roll) * z[0] + std::sin(roll) * level_edge[0],
                      std::cos(roll) * z[1] + std::sin(roll) * level_edge[1],
                      std::cos(roll) * z[2] + std::sin(roll) * level_edge[2]};
  const Vec3 x_rolled = cross(y, z_rolled);
  const double facing = std::fmod(deg(std::atan2(x_rolled[0], x_rolled[1])) + 90 + 360, 360);
  const AxisTilt read = axisTilt({x_rolled[2], y[2], z_rolled[2], {}});
  EXPECT_GT(std::abs(read.y_deg), 4);  // the sensor sees the roll
  EXPECT_NEAR(sun::incidenceAngleDeg(moduleOrientation(read, facing), {30, 180}), 10, 1e-9);
}

// ----------------------------------------------------------------------------- measureTilt

TEST(MeasureTilt, AveragesAndReportsTheScatter) {
  // 60 µg per axis at tilt 30: the ADXL355's noise at the driver's data rate.
  ScriptedInclinometer sensor(noisySamples({30, 0}, 400, 60e-6));
  TiltOptions options;
  options.samples = 400;
  const auto reading = measureTilt(sensor, options);
  ASSERT_TRUE(reading) << reading.error().message;
  // σ ≈ 60 µg ≈ 0.0034° per sample; the mean of 400 is ±0.00017°: 0.001° is 6σ.
  EXPECT_NEAR(reading->module_tilt_deg, 30, 1e-3);
  EXPECT_NEAR(reading->tilt_std_deg, deg(60e-6), deg(60e-6) * 0.2);  // ±20 %: 400 samples
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
  samples[3] = hardwareError("adxl355:/dev/i2c-1@0x1d: saturated");
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

// --------------------------------------------------------------------------- flip calibration

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

// ------------------------------------------------------------------------------ incidence angle

// α on geometries whose answer is known by construction. The issue's bound is 0.05°; these are
// exact in doubles.
TEST(IncidenceAngle, ConstructedGeometries) {
  EXPECT_NEAR(sun::incidenceAngleDeg({0, 180}, {35, 123}), 55, kExactDeg);  // flat: 90° − elevation
  EXPECT_NEAR(sun::incidenceAngleDeg({30, 180}, {60, 180}), 0,
              1e-6);                                                // sun on the normal (acos at 1)
  EXPECT_NEAR(sun::incidenceAngleDeg({90, 90}, {0, 90}), 0, 1e-6);  // vertical east wall, sunrise
  EXPECT_NEAR(sun::incidenceAngleDeg({90, 90}, {0, 180}), 90, kExactDeg);
  EXPECT_NEAR(sun::incidenceAngleDeg({90, 90}, {0, 270}), 180, 1e-6);  // behind
  EXPECT_NEAR(sun::incidenceAngleDeg({30, 180}, {30, 180}), 30, kExactDeg);
  EXPECT_NEAR(sun::incidenceAngleDeg({30, 180}, {30, 180 + 360}), 30, kExactDeg);
}

// Against the textbook formula (Duffie & Beckman, Solar Engineering of Thermal Processes, eq.
// 1.6.5 with the zenith angle): cos α = cos θz cos β + sin θz sin β cos(γs − γ).
TEST(IncidenceAngle, AgreesWithTheTextbookFormula) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> tilt(0, 90), azimuth(0, 360), elevation(0, 90);
  for (int i = 0; i < 1000; ++i) {
    const sun::ModuleOrientation module{tilt(random), azimuth(random)};
    const sun::SkyDirection sun{elevation(random), azimuth(random)};
    const double zenith = rad(90 - sun.elevation_deg);
    const double cosine = std::cos(zenith) * std::cos(rad(module.tilt_deg)) +
                          std::sin(zenith) * std::sin(rad(module.tilt_deg)) *
                              std::cos(rad(sun.azimuth_deg - module.azimuth_deg));
    // acos near 0° amplifies rounding (1e-16 in the cosine → 1e-6°): 1e-6° is rounding.
    EXPECT_NEAR(sun::incidenceAngleDeg(module, sun), deg(std::acos(std::clamp(cosine, -1.0, 1.0))),
                1e-6);
  }
}

// ---------------------------------------------------------------------------------- clock

TEST(ClockStatus, InterpretsAdjtimex) {
  const sun::ClockStatus synced = sun::interpretClockState(TIME_OK, 0, 250000, 1200);
  EXPECT_TRUE(synced.synchronised);
  EXPECT_DOUBLE_EQ(*synced.uncertaintyS(), 0.0012);
  // Unsynchronised, the kernel's 16 s is a cap, not a bound: the error is unknown.
  const sun::ClockStatus error =
      sun::interpretClockState(TIME_ERROR, STA_UNSYNC, 16000000, 16000000);
  EXPECT_FALSE(error.synchronised);
  EXPECT_FALSE(error.uncertaintyS());
  EXPECT_NE(error.detail.find("unsynchronised"), std::string::npos);
  EXPECT_FALSE(sun::interpretClockState(TIME_OK, STA_UNSYNC, 0, 0).synchronised);
  EXPECT_FALSE(sun::interpretClockState(TIME_ERROR, 0, 0, 0).synchronised);
  EXPECT_TRUE(
      sun::interpretClockState(TIME_INS, STA_PLL, 1, 1).synchronised);  // leap second pending
}

// ---------------------------------------------------------------------------------- config

// A config file holding only the rig's sections (glarecamd's config holds more:
// daemon::readConfig reads it whole).
Result<RigConfig> readRigConfig(const std::filesystem::path& path) {
  toml::table root;
  GLARECAM_ASSIGN(root, readConfigFile(path, kRigSections));
  return readRigSections(path, root);
}

std::filesystem::path writeText(const TempDir& dir, const std::string& name,
                                const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

constexpr const char* kSunConfig = R"(calibration = "calib.json"
[site]
latitude_deg = 39.742476
longitude_deg = -105.1786
altitude_m = 1830.14
pressure_hpa = 820
temperature_c = 11

[module]
azimuth_deg = 180

[inclinometer]
uri = "sim:30"
samples = 20
)";

TEST(RigConfig, ReadsEverySection) {
  TempDir dir;
  const auto config = readRigConfig(writeText(dir, "rig.toml", kSunConfig));
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(config->site);
  EXPECT_DOUBLE_EQ(config->site->latitude_deg, 39.742476);
  EXPECT_DOUBLE_EQ(config->site->pressure_hpa, 820);
  EXPECT_EQ(*config->calibration, dir / "calib.json");  // relative to the config file
  EXPECT_EQ(config->inclinometer->uri, "sim:30");
  EXPECT_EQ(config->inclinometer->tilt.samples, 20);
  EXPECT_DOUBLE_EQ(*config->module_azimuth_deg, 180);
  EXPECT_FALSE(config->fixed_source);
}

TEST(RigConfig, PressureDefaultsToTheStandardAtmosphere) {
  // ISO 2533: 1013.25 hPa at sea level, 898.7 hPa at 1000 m, 795.0 hPa at 2000 m (tabulated to
  // 0.1 hPa).
  EXPECT_NEAR(sun::standardPressureHpa(0), 1013.25, 1e-9);
  EXPECT_NEAR(sun::standardPressureHpa(1000), 898.75, 0.1);
  EXPECT_NEAR(sun::standardPressureHpa(2000), 795.01, 0.1);
  TempDir dir;
  const auto config =
      readRigConfig(writeText(dir, "rig.toml",
                              "[site]\nlatitude_deg = 1\nlongitude_deg = 2\naltitude_m = 1000\n"
                              "[module]\nazimuth_deg = 0\ntilt_deg = 10\n"));
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_NEAR(config->site->pressure_hpa, 898.75, 0.1);
}

struct BadConfig {
  const char* text;
  const char* message;  // the error must contain this
};

TEST(RigConfig, BadConfigsNameTheFileLineAndProblem) {
  const BadConfig cases[] = {
      {"[site]\nlatitude_deg = 91\nlongitude_deg = 0\n",
       "rig.toml:2: site.latitude_deg = 91 is outside [-90, 90]"},
      {"[site]\nlatitude_deg = \"north\"\nlongitude_deg = 0\n",
       "rig.toml:2: site.latitude_deg must be a number"},
      {"[site]\nlongitude_deg = 0\n", "rig.toml:1: [site] needs latitude_deg"},
      {"[site]\nlatitude_deg = 1\nlongitude_deg = 0\nlattitude = 3\n",
       "rig.toml:4: unknown key site.lattitude"},
      {"[sight]\nx = 1\n", "rig.toml:1: unknown section [sight]"},
      {"[site]\nlatitude_deg = 1\nlongitude_deg = 0\n[source]\nelevation_deg = 0\nazimuth_deg = 0\n"
       "[module]\nazimuth_deg = 0\n",
       "not both"},
      {"[site]\nlatitude_deg = 1\nlongitude_deg = 0\n", "[module] azimuth_deg is needed"},
      {"[inclinometer]\nsamples = 5\n", "[inclinometer] needs uri"},
      {"[inclinometer]\nuri = \"sim:0\"\nsamples = 1\n",
       "rig.toml:3: inclinometer.samples = 1 is outside"},
      {"[site\nlatitude_deg = 1\n", "rig.toml:1:"},
      {"camera = 5\n", "rig.toml:1: camera must be a non-empty string"},
      {"[site]\nlatitude_deg = nan\nlongitude_deg = 0\n", "site.latitude_deg must be a number"},
  };
  for (const BadConfig& c : cases) {
    TempDir dir;
    const auto config = readRigConfig(writeText(dir, "rig.toml", c.text));
    ASSERT_FALSE(config) << c.text;
    EXPECT_EQ(config.error().code, ErrorCode::kBadInput);
    EXPECT_NE(config.error().message.find(c.message), std::string::npos)
        << "got: " << config.error().message << "\nwant: " << c.message;
    EXPECT_EQ(config.error().message.find('\n'), std::string::npos) << config.error().message;
  }
  const auto missing = readRigConfig("/nonexistent/rig.toml");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("/nonexistent/rig.toml: no such file"), std::string::npos);
}

TEST(RigConfig, ReadsTheGpioLines) {
  TempDir dir;
  const auto config = readRigConfig(writeText(dir, "rig.toml", R"([gpio]
chip = "pinctrl-bcm2711"
led = 17
trigger = "GPIO22"
trigger_active_low = true
button = 27
button_active_low = true
button_pull_up = false
debounce_ms = 30
trigger_pulse_us = 500
)"));
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(config->gpio);
  EXPECT_EQ(config->gpio->chip, "pinctrl-bcm2711");
  EXPECT_EQ(std::get<unsigned>(config->gpio->led->line), 17u);
  EXPECT_FALSE(config->gpio->led->active_low);
  EXPECT_EQ(std::get<std::string>(config->gpio->trigger->line), "GPIO22");
  EXPECT_TRUE(config->gpio->trigger->active_low);
  EXPECT_TRUE(config->gpio->button->active_low);
  EXPECT_FALSE(config->gpio->button_pull_up);
  EXPECT_EQ(config->gpio->debounce, std::chrono::milliseconds(30));
  EXPECT_EQ(config->gpio->trigger_pulse, std::chrono::microseconds(500));
}

TEST(RigConfig, AButtonOnThePullUpIsActiveLowByDefault) {
  TempDir dir;
  const auto pulled = readRigConfig(writeText(dir, "a.toml", "[gpio]\nbutton = 22\n"));
  ASSERT_TRUE(pulled) << pulled.error().message;
  EXPECT_TRUE(pulled->gpio->button->active_low);
  const auto external =
      readRigConfig(writeText(dir, "b.toml", "[gpio]\nbutton = 22\nbutton_pull_up = false\n"));
  ASSERT_TRUE(external) << external.error().message;
  EXPECT_FALSE(external->gpio->button->active_low);
}

TEST(RigConfig, BadGpioLinesNameTheLine) {
  const BadConfig cases[] = {
      {"[gpio]\nled = 1.5\n", "rig.toml:2: gpio.led must be a line offset"},
      {"[gpio]\nled = \"\"\n", "rig.toml:2: gpio.led must be a line offset"},
      {"[gpio]\nled = 3\nled_active_low = 1\n",
       "rig.toml:3: gpio.led_active_low must be true or false"},
      {"[gpio]\nbuton = 3\n", "rig.toml:2: unknown key gpio.buton"},
      {"[gpio]\nled = 3\nbutton = 3\n", "rig.toml:1: [gpio]"},
      {"[gpio]\ndebounce_ms = 5000\n", "gpio.debounce_ms = 5000 is outside [0, 1000]"},
      {"[gpio]\ntrigger_pulse_us = 0\n", "gpio.trigger_pulse_us = 0 is outside"},
  };
  for (const BadConfig& c : cases) {
    TempDir dir;
    const auto config = readRigConfig(writeText(dir, "rig.toml", c.text));
    ASSERT_FALSE(config) << c.text;
    EXPECT_NE(config.error().message.find(c.message), std::string::npos)
        << "got: " << config.error().message << "\nwant: " << c.message;
  }
}

// -------------------------------------------------------------------------- rig geometry

// A reading of a module tilted `tilt_deg` about the sensor's x axis (not rolled).
TiltReading readingOf(double tilt_deg, double uncertainty_deg = 0) {
  TiltReading reading;
  reading.tilt = reading.raw_tilt = {tilt_deg, 0};
  reading.module_tilt_deg = tilt_deg;
  reading.tilt_uncertainty_deg = uncertainty_deg;
  return reading;
}

RigConfig labConfig() {
  RigConfig config;
  config.path = "lab.toml";
  config.fixed_source = sun::SkyDirection{0, 180};  // a lamp on the horizon, due south
  config.module_azimuth_deg = 180;
  return config;
}

TEST(RigGeometry, LabModeTakesAlphaFromTheTiltAlone) {
  RigConfig config = labConfig();
  // Normal at 30° elevation: 30° from the horizontal lamp.
  const TiltReading tilt = readingOf(60, 0.01);
  const auto g = computeRigGeometry(config, tilt, {}, sun::ClockStatus{});
  ASSERT_TRUE(g) << g.error().message;
  EXPECT_EQ(g->source, GeometrySource::kFixed);
  EXPECT_NEAR(g->alpha_deg, 30, kExactDeg);
  // dα/dβ = 1 here, so α inherits the tilt's uncertainty, and nothing from the clock.
  EXPECT_NEAR(g->alpha_uncertainty_deg, 0.01, 1e-6);
  EXPECT_EQ(g->alpha_uncertainty_clock_deg, 0);
  const nlohmann::json block = geometryJson(*g);
  EXPECT_EQ(block["source"], "fixed");
  EXPECT_DOUBLE_EQ(block["module_tilt_deg"].get<double>(), 60);
  EXPECT_FALSE(block.contains("sun_elevation_deg"));
}

// The reading's uncertainty is the same in every direction: with the source side-on to the tilt
// (where ∂α/∂β vanishes) α still inherits it, through the normal's sideways error.
TEST(RigGeometry, TheTiltUncertaintyCountsInEveryDirection) {
  RigConfig config = labConfig();
  config.fixed_source = sun::SkyDirection{0, 90};  // due east; the module faces south
  const auto g = computeRigGeometry(config, readingOf(30, 0.01), {}, sun::ClockStatus{});
  ASSERT_TRUE(g);
  EXPECT_NEAR(g->alpha_uncertainty_deg, 0.01, 1e-12);
}

TEST(RigGeometry, NormalIncidenceStillCarriesTheTiltUncertainty) {
  // Normal on the lamp: α = 0, where a central difference is 0.
  const TiltReading tilt = readingOf(90, 0.02);
  const auto g = computeRigGeometry(labConfig(), tilt, {}, sun::ClockStatus{});
  ASSERT_TRUE(g);
  EXPECT_NEAR(g->alpha_deg, 0, 1e-6);
  EXPECT_NEAR(g->alpha_uncertainty_deg, 0.02, 1e-4);
}

TEST(RigGeometry, SunModeUsesTheSolarPositionAndTheClock) {
  TempDir dir;
  auto config = readRigConfig(writeText(dir, "rig.toml", kSunConfig));
  ASSERT_TRUE(config);
  // NREL SPA's test case (Reda & Andreas 2008, table A4.1): zenith 50.11162°, azimuth 194.34024°.
  const auto time = sun::parseIsoTime("2003-10-17T12:30:30-07:00");
  ASSERT_TRUE(time);
  const TiltReading tilt = readingOf(50.11162);  // facing the sun exactly: α = 0 up to the model
  config->module_azimuth_deg = 194.34024;
  const sun::ClockStatus synced = sun::interpretClockState(TIME_OK, 0, 1000, 1000);
  const auto g = computeRigGeometry(*config, tilt, *time, synced);
  ASSERT_TRUE(g) << g.error().message;
  // SPA's own uncertainty is ±0.0003°; the published values have 5 decimals.
  EXPECT_NEAR(g->alpha_deg, 0, 1e-3);
  ASSERT_TRUE(g->sun);
  EXPECT_NEAR(g->sun->zenith_deg, 50.11162, 1e-4);
  EXPECT_TRUE(g->warnings.empty());
  // A clock synchronised to ±0.5 s: the sun moves at most 15°/h = 0.0042°/s, α no faster.
  const sun::ClockStatus half_second = sun::interpretClockState(TIME_OK, 0, 1000000, 500000);
  const auto h = computeRigGeometry(*config, tilt, *time, half_second);
  ASSERT_TRUE(h);
  EXPECT_GT(h->alpha_uncertainty_clock_deg, 0.0005);
  EXPECT_LT(h->alpha_uncertainty_clock_deg, 0.5 * 0.0042 * 1.05);
  // Unsynchronised: the clock's share is unknown, left out and said so.
  const sun::ClockStatus unsynced =
      sun::interpretClockState(TIME_ERROR, STA_UNSYNC, 16000000, 16000000);
  const auto u = computeRigGeometry(*config, tilt, *time, unsynced);
  ASSERT_TRUE(u);
  EXPECT_TRUE(u->clock_error_unknown);
  EXPECT_EQ(u->alpha_uncertainty_clock_deg, 0);
  ASSERT_EQ(u->warnings.size(), 1u);
  EXPECT_NE(u->warnings[0].find("not synchronised"), std::string::npos);
  // A time given by the user: no clock involved at all.
  const auto given = computeRigGeometry(*config, tilt, *time, std::nullopt);
  ASSERT_TRUE(given);
  EXPECT_FALSE(given->clock);
  EXPECT_TRUE(given->warnings.empty());
  EXPECT_FALSE(geometryJson(*given).contains("clock_synchronised"));
  const nlohmann::json block = geometryJson(*u);
  EXPECT_EQ(block["clock_synchronised"], false);
  EXPECT_EQ(block["alpha_uncertainty_excludes_clock"], true);
  EXPECT_NEAR(block["sun_azimuth_deg"].get<double>(), 194.34024, 1e-4);
}

TEST(RigGeometry, WarnsWhenTheSunIsBelowTheHorizonOrBehind) {
  RigConfig config = labConfig();
  config.fixed_source = sun::SkyDirection{10, 0};  // north, behind a south-facing upright module
  const auto g = computeRigGeometry(config, readingOf(90), {}, sun::ClockStatus{});
  ASSERT_TRUE(g);
  EXPECT_GT(g->alpha_deg, 90);
  ASSERT_EQ(g->warnings.size(), 1u);
  EXPECT_NE(g->warnings[0].find("behind the module"), std::string::npos);
}

TEST(RigGeometry, NeedsASourceAndATilt) {
  RigConfig config;
  config.path = "x.toml";
  EXPECT_EQ(computeRigGeometry(config, {}, {}, {}).error().code, ErrorCode::kBadInput);
  config = labConfig();
  const auto no_tilt = computeRigGeometry(config, std::nullopt, {}, {});
  ASSERT_FALSE(no_tilt);
  EXPECT_NE(no_tilt.error().message.find("no module tilt"), std::string::npos);
  config.module_tilt_deg = 60;  // a fixed tilt instead of an inclinometer
  EXPECT_NEAR(computeRigGeometry(config, std::nullopt, {}, {})->alpha_deg, 30, kExactDeg);
}

TEST(RigSensors, MeasuresThroughTheSimulatedInclinometerWithTheStoredOffset) {
  TempDir dir;
  // A module at 60° whose sensor is mounted 0.5° off: the stored flip offset removes it.
  writeText(dir, "rig.toml",
            "calibration = \"calib.json\"\n[source]\nelevation_deg = 0\nazimuth_deg = 180\n"
            "[module]\nazimuth_deg = 180\n[inclinometer]\nuri = \"sim:60,offset_x_deg=0.5\"\n");
  const auto config = readRigConfig(dir / "rig.toml");
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(writeZeroOffset(dir / "calib.json", {{0.5, 0}, 0.001, ""}, {{"method", "flip"}}));
  auto sensors = RigSensors::open(*config);
  ASSERT_TRUE(sensors) << sensors.error().message;
  const auto g = (*sensors)->measure({});
  ASSERT_TRUE(g) << g.error().message;
  // The simulator's noise (60 µg ≈ 0.0034° per sample, 50 samples): 0.005° is > 5σ of the mean.
  EXPECT_NEAR(g->module.tilt_deg, 60, 0.005);
  EXPECT_NEAR(g->alpha_deg, 30, 0.005);
  EXPECT_EQ(g->inclinometer_uri, "sim:60,offset_x_deg=0.5");
  EXPECT_EQ(geometryJson(*g)["inclinometer"]["uri"], "sim:60,offset_x_deg=0.5");
}

TEST(RigSensors, AMissingCalibrationFileIsAWarningRecordedInEachGeometry) {
  TempDir dir;
  writeText(dir, "rig.toml",
            "calibration = \"not-yet.json\"\n[source]\nelevation_deg = 0\nazimuth_deg = 180\n"
            "[module]\nazimuth_deg = 180\n[inclinometer]\nuri = \"sim:60\"\n");
  const auto config = readRigConfig(dir / "rig.toml");
  ASSERT_TRUE(config) << config.error().message;
  auto sensors = RigSensors::open(*config);
  ASSERT_TRUE(sensors) << sensors.error().message;
  EXPECT_FALSE((*sensors)->zeroOffset());
  const auto g = (*sensors)->measure({});
  ASSERT_TRUE(g);
  ASSERT_EQ(g->warnings.size(), 1u);
  EXPECT_NE(g->warnings[0].find("not-yet.json"), std::string::npos) << g->warnings[0];
  const nlohmann::json block = geometryJson(*g);
  EXPECT_TRUE(block["inclinometer"]["zero_offset_x_deg"].is_null());
  EXPECT_EQ(block["warnings"].size(), 1u);
}

TEST(RigSensors, AnOffsetMeasuredWithAnotherSensorIsWarnedAbout) {
  TempDir dir;
  writeText(dir, "rig.toml",
            "calibration = \"calib.json\"\n[source]\nelevation_deg = 0\nazimuth_deg = 180\n"
            "[module]\nazimuth_deg = 180\n[inclinometer]\nuri = \"sim:60\"\n");
  ASSERT_TRUE(writeZeroOffset(dir / "calib.json", {{0.1, 0}, 0.001, ""},
                              {{"uri", "adxl355:/dev/i2c-1@0x53"}}));
  auto sensors = RigSensors::open(*readRigConfig(dir / "rig.toml"));
  ASSERT_TRUE(sensors);
  const auto g = (*sensors)->measure({});
  ASSERT_TRUE(g);
  ASSERT_EQ(g->warnings.size(), 1u);
  EXPECT_NE(g->warnings[0].find("measured with adxl355:/dev/i2c-1@0x53"), std::string::npos);
  EXPECT_DOUBLE_EQ(geometryJson(*g)["inclinometer"]["zero_offset_x_deg"].get<double>(), 0.1);
}

// The sun moves between the tilt reading and the bracket: retime() gives α later, same tilt.
TEST(RigSensors, RetimeMovesTheSunNotTheModule) {
  TempDir dir;
  const auto config = readRigConfig(writeText(dir, "rig.toml", kSunConfig));
  ASSERT_TRUE(config) << config.error().message;
  auto sensors = RigSensors::open(*config);
  ASSERT_TRUE(sensors) << sensors.error().message;
  const auto time = sun::parseIsoTime("2003-10-17T19:30:30Z");
  const auto first = (*sensors)->measure(*time, {}, false);
  ASSERT_TRUE(first);
  const auto later = (*sensors)->retime(*first, *time + std::chrono::minutes(10));
  ASSERT_TRUE(later);
  EXPECT_EQ(later->module.tilt_deg, first->module.tilt_deg);
  // Ten minutes of sun: 2.5° at most (15°/h), and clearly more than nothing.
  EXPECT_GT(std::abs(later->sun->azimuth_deg - first->sun->azimuth_deg), 0.5);
  EXPECT_LT(std::abs(later->alpha_deg - first->alpha_deg), 2.5);
  EXPECT_NE(later->alpha_deg, first->alpha_deg);
}

// ---------------------------------------------------------------- the calibration file block

TEST(ZeroOffsetFile, MergesIntoAnExistingCalibrationAndReadsBack) {
  TempDir dir;
  writeText(dir, "calib.json", R"({"black_level_dn": 64, "luminance_factor": 2.5})");
  ASSERT_TRUE(writeZeroOffset(dir / "calib.json", {{0.25, -0.125}, 0.002, ""},
                              {{"method", "flip"}, {"date", "2026-11-26T08:00:00Z"}}));
  const auto document = readJsonFile((dir / "calib.json").string());
  ASSERT_TRUE(document);
  EXPECT_EQ((*document)["black_level_dn"], 64);  // other keys kept
  EXPECT_EQ((*document)["inclinometer"]["method"], "flip");
  const auto zero = readZeroOffset(dir / "calib.json");
  ASSERT_TRUE(zero && *zero);
  EXPECT_DOUBLE_EQ((*zero)->offset.x_deg, 0.25);
  EXPECT_DOUBLE_EQ((*zero)->offset.y_deg, -0.125);
  EXPECT_DOUBLE_EQ((*zero)->uncertainty_deg, 0.002);
}

TEST(ZeroOffsetFile, BadFilesAreNamedAndNeverOverwritten) {
  TempDir dir;
  writeText(dir, "none.json", R"({"black_level_dn": 64})");
  const auto none = readZeroOffset(dir / "none.json");
  ASSERT_TRUE(none);
  EXPECT_FALSE(*none);
  writeText(dir, "bad.json", "{not json");
  EXPECT_FALSE(readZeroOffset(dir / "bad.json"));
  EXPECT_FALSE(writeZeroOffset(dir / "bad.json", {}, {}));
  std::ifstream in(dir / "bad.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "{not json");
  writeText(dir, "str.json",
            R"({"inclinometer": {"zero_offset_x_deg": "0.3", "zero_offset_y_deg": 0}})");
  const auto str = readZeroOffset(dir / "str.json");
  ASSERT_FALSE(str);
  EXPECT_NE(str.error().message.find(
                "str.json: inclinometer: \"zero_offset_x_deg\" must be a finite number"),
            std::string::npos)
      << str.error().message;
  writeText(dir, "big.json",
            R"({"inclinometer": {"zero_offset_x_deg": 30, "zero_offset_y_deg": 0}})");
  EXPECT_NE(readZeroOffset(dir / "big.json").error().message.find("implausibly large"),
            std::string::npos);
  writeText(
      dir, "neg.json",
      R"({"inclinometer": {"zero_offset_x_deg": 0, "zero_offset_y_deg": 0, "uncertainty_deg": -1}})");
  EXPECT_FALSE(readZeroOffset(dir / "neg.json"));
  EXPECT_FALSE(writeZeroOffset(dir / "nan.json", {{std::nan(""), 0}, 0, ""}, {}));
  EXPECT_FALSE(std::filesystem::exists(dir / "nan.json"));
}

TEST(TiltReadingJson, RoundTripsTheRawTilts) {
  ScriptedInclinometer sensor(noisySamples({12, -3}, 50, 60e-6));
  const auto reading = measureTilt(sensor, {});
  ASSERT_TRUE(reading);
  const auto back = parseTiltReading(tiltReadingJson(*reading), "r.json");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_DOUBLE_EQ(back->raw_tilt.x_deg, reading->raw_tilt.x_deg);
  EXPECT_DOUBLE_EQ(back->tilt_std_deg, reading->tilt_std_deg);
  EXPECT_EQ(back->samples, 50);
  EXPECT_FALSE(parseTiltReading(nlohmann::json::array(), "r.json"));
  nlohmann::json huge = tiltReadingJson(*reading);
  huge["samples"] = 1e30;  // would overflow an int
  EXPECT_FALSE(parseTiltReading(huge, "r.json"));
  nlohmann::json negative = tiltReadingJson(*reading);
  negative["tilt_std_deg"] = -1;
  EXPECT_FALSE(parseTiltReading(negative, "r.json"));
  EXPECT_FALSE(parseTiltReading({{"raw_tilt_x_deg", 1}}, "r.json"));
}

// ------------------------------------------------------------------------ inclinometer URIs

TEST(InclinometerRegistry, UnknownSchemesAndMalformedUrisAreBadInput) {
  for (const char* uri : {"", "sim", "adxl", "foo:bar", "/dev/i2c-1"}) {
    const auto opened = openInclinometer(uri);
    ASSERT_FALSE(opened) << uri;
    EXPECT_EQ(opened.error().code, ErrorCode::kBadInput) << uri;
  }
  for (const char* uri :
       {"sim:", "sim:abc", "sim:30,noise_g", "sim:30,noise_g=-1", "sim:30,colour=red",
        "sim:30,fault=smoke", "sim:200", "sim:30,seed=1.5"}) {
    const auto opened = openInclinometer(uri);
    ASSERT_FALSE(opened) << uri;
    EXPECT_EQ(opened.error().code, ErrorCode::kBadInput) << uri;
    EXPECT_NE(opened.error().message.find("inclinometer URI sim:"), std::string::npos)
        << opened.error().message;
  }
}

TEST(InclinometerRegistry, SimReadsItsTilt) {
  auto sensor = openInclinometer("sim:25,roll_deg=-3,noise_g=0");
  ASSERT_TRUE(sensor) << sensor.error().message;
  EXPECT_EQ((*sensor)->info().backend, "sim");
  const auto reading = measureTilt(**sensor, {});
  ASSERT_TRUE(reading) << reading.error().message;
  // Noise-free: the only error is the ADXL355's 20-bit quantisation, 3.9 µg ≈ 0.0002° at ±2 g.
  EXPECT_NEAR(reading->tilt.x_deg, 25, 5e-4);
  EXPECT_NEAR(reading->tilt.y_deg, -3, 5e-4);
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
  EXPECT_NEAR(a->tilt_std_deg, deg(60e-6), 0.3 * deg(60e-6));
  EXPECT_NEAR(b->tilt_std_deg, deg(60e-6), 0.3 * deg(60e-6));
}

TEST(InclinometerRegistry, SimFaultsAreErrorsNotHangs) {
  for (const char* fault : {"absent", "wrong-id"}) {
    const auto opened = openInclinometer(std::string("sim:0,fault=") + fault);
    ASSERT_FALSE(opened) << fault;
    EXPECT_EQ(opened.error().code, ErrorCode::kHardware) << fault;
  }
  for (const char* fault : {"zeros", "saturated", "never-ready"}) {
    auto sensor = openInclinometer(std::string("sim:0,fault=") + fault);
    ASSERT_TRUE(sensor) << fault << ": " << sensor.error().message;
    const auto sample = (*sensor)->read();
    ASSERT_FALSE(sample) << fault;
    EXPECT_EQ(sample.error().code, ErrorCode::kHardware) << fault;
  }
}

TEST(InclinometerRegistry, RealBusesAbsentHereFailClearly) {
  const auto i2c = openInclinometer("adxl355:/dev/i2c-97@0x1d");
  ASSERT_FALSE(i2c);
  EXPECT_EQ(i2c.error().code, ErrorCode::kHardware);
  EXPECT_NE(i2c.error().message.find("/dev/i2c-97"), std::string::npos) << i2c.error().message;
  const auto iio = openInclinometer("iio:iio:device97");
  ASSERT_FALSE(iio);
  EXPECT_NE(iio.error().message.find("iio:device97"), std::string::npos) << iio.error().message;
}

}  // namespace
}  // namespace glarecam::rig
