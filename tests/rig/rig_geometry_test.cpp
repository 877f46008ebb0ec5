// The rig's geometry: α from the tilt and a fixed source or the sun and the clock, with its
// uncertainty and warnings, and the rig's sensors measuring it through the simulated inclinometer
// with the stored zero offset.
#include "rig/rig_geometry.h"

#include <gtest/gtest.h>
#include <sys/timex.h>

#include <chrono>
#include <cmath>

#include "core/time.h"
#include "rig/inclinometer/zero_offset_file.h"
#include "rig/rig_config_test_support.h"
#include "sun/clock_sync.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

using testing::kExactDeg;
using testing::kSunConfig;
using testing::readRigConfig;
using testing::TempDir;
using testing::writeText;

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
  const auto time = parseIsoTime("2003-10-17T12:30:30-07:00");
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
  const auto time = parseIsoTime("2003-10-17T19:30:30Z");
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

}  // namespace
}  // namespace glarecam::rig
