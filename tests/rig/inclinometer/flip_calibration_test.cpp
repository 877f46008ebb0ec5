// The flip calibration: two readings from saved files or taken now with a turn between them, each
// near level, and the zero offset they give stored with both readings as its provenance, unless
// it is implausible.
#include "rig/inclinometer/flip_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/json.h"
#include "rig/inclinometer/scripted_inclinometer.h"
#include "rig/inclinometer/zero_offset_file.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

namespace fs = std::filesystem;
using testing::noisySamples;
using testing::ScriptedInclinometer;
using testing::TempDir;

// A sensor mounted 0.3° × -0.2° off on a surface 0.8° × 0.5° off level: its first reading, and
// its second with the frame turned 180° on the surface.
constexpr AxisTilt kOffset{0.3, -0.2};
constexpr AxisTilt kSurface{0.8, 0.5};
constexpr AxisTilt kTurned{-0.8, -0.5};

TiltReading readingOf(AxisTilt surface, AxisTilt offset = kOffset) {
  ScriptedInclinometer sensor(noisySamples(surface, 50, 0, offset));
  auto reading = measureTilt(sensor, {});
  EXPECT_TRUE(reading) << reading.error().message;
  return reading.value_or(TiltReading{});
}

// A saved reading, as `glarecam inclinometer read --out` writes it.
fs::path saveReading(const fs::path& path, const TiltReading& reading, const std::string& uri) {
  nlohmann::json record = tiltReadingJson(reading);
  record["uri"] = uri;
  testing::writeText(path, record.dump());
  return path;
}

FlipReadings flipOf(const TiltReading& first, const TiltReading& second) {
  return {{first, tiltReadingJson(first), "sim:0"}, {second, tiltReadingJson(second), "sim:0"}};
}

TEST(FlipReadings, SavedReadingsAreReadWithTheirSensor) {
  TempDir dir;
  const auto first = saveReading(dir / "a.json", readingOf(kSurface), "adxl355:/dev/i2c-1@0x1d");
  const auto second = saveReading(dir / "b.json", readingOf(kTurned), "adxl355:/dev/i2c-1@0x1d");
  const auto readings = savedFlipReadings(first, second);
  ASSERT_TRUE(readings) << readings.error().message;
  EXPECT_EQ(readings->first.uri, "adxl355:/dev/i2c-1@0x1d");
  EXPECT_DOUBLE_EQ(readings->first.reading.raw_tilt.x_deg, readingOf(kSurface).raw_tilt.x_deg);
  EXPECT_DOUBLE_EQ(readings->second.reading.raw_tilt.y_deg, readingOf(kTurned).raw_tilt.y_deg);
  EXPECT_EQ(readings->second.record["uri"], "adxl355:/dev/i2c-1@0x1d");
}

TEST(FlipReadings, TheSameReadingTwiceIsRefused) {
  TempDir dir;
  const auto first = saveReading(dir / "a.json", readingOf(kSurface), "sim:0");
  const auto same = savedFlipReadings(first, first);
  ASSERT_FALSE(same);
  EXPECT_EQ(same.error().code, ErrorCode::kBadInput);
  EXPECT_NE(same.error().message.find("names the same reading twice"), std::string::npos);
  const auto copy = saveReading(dir / "copy.json", readingOf(kSurface), "sim:0");
  const auto twice = savedFlipReadings(first, copy);
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.error().message.find("hold the same reading"), std::string::npos)
      << twice.error().message;
  const auto missing = savedFlipReadings(first, dir / "missing.json");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("missing.json"), std::string::npos);
}

TEST(FlipReadings, TakenNowWithTheTurnBetweenThem) {
  auto samples = noisySamples(kSurface, 50, 0, kOffset);
  for (auto& sample : noisySamples(kTurned, 50, 0, kOffset)) samples.push_back(sample);
  ScriptedInclinometer sensor(std::move(samples));
  int turns = 0;
  const auto readings =
      takeFlipReadings(sensor, "sim:0", {}, [&](const TiltReading& first) -> Status {
        ++turns;
        EXPECT_NEAR(first.raw_tilt.x_deg, kSurface.x_deg + kOffset.x_deg, 0.01);
        return {};
      });
  ASSERT_TRUE(readings) << readings.error().message;
  EXPECT_EQ(turns, 1);
  EXPECT_EQ(readings->first.uri, "sim:0");
  EXPECT_EQ(readings->first.record["uri"], "sim:0");
  EXPECT_TRUE(readings->second.record.contains("time"));
  EXPECT_NEAR(readings->second.reading.raw_tilt.x_deg, kTurned.x_deg + kOffset.x_deg, 0.01);
}

TEST(FlipReadings, AFirstReadingFarFromLevelEndsItBeforeTheTurn) {
  ScriptedInclinometer sensor(noisySamples({12, 0}, 50, 0));
  int turns = 0;
  const auto readings = takeFlipReadings(sensor, "sim:12", {}, [&](const TiltReading&) -> Status {
    ++turns;
    return {};
  });
  ASSERT_FALSE(readings);
  EXPECT_EQ(readings.error().code, ErrorCode::kBadInput);
  EXPECT_NE(readings.error().message.find("within a few degrees of level (at most 10°)"),
            std::string::npos)
      << readings.error().message;
  EXPECT_EQ(turns, 0);
  // The operator's answer at the turn ends it too.
  ScriptedInclinometer level(noisySamples(kSurface, 100, 0));
  const auto cancelled = takeFlipReadings(level, "sim:0", {}, [](const TiltReading&) -> Status {
    return badInput("inclinometer flip: cancelled");
  });
  ASSERT_FALSE(cancelled);
  EXPECT_EQ(cancelled.error().message, "inclinometer flip: cancelled");
}

TEST(FlipReadings, NearLevelIsWithinTheLargestPlausibleOffsetOnBothAxes) {
  TiltReading reading;
  reading.raw_tilt = {kMaxPlausibleZeroOffsetDeg, -kMaxPlausibleZeroOffsetDeg};
  EXPECT_TRUE(checkNearLevel(reading));
  reading.raw_tilt.y_deg = -kMaxPlausibleZeroOffsetDeg - 0.01;
  const Status tilted = checkNearLevel(reading);
  ASSERT_FALSE(tilted);
  EXPECT_NE(tilted.error().message.find("reads tilt x 10.00°, y -10.01°"), std::string::npos)
      << tilted.error().message;
}

TEST(StoreFlipCalibration, StoresTheOffsetWithBothReadingsAsProvenance) {
  TempDir dir;
  testing::writeText(dir / "calib.json", R"({"black_level_dn": 64})");
  const auto flip = storeFlipCalibration(dir / "calib.json",
                                         flipOf(readingOf(kSurface), readingOf(kTurned)), "sim:0");
  ASSERT_TRUE(flip) << flip.error().message;
  // The bisector is exact on any surface (tilt_test.cpp); noise-free samples: rounding only.
  EXPECT_NEAR(flip->zero.offset.x_deg, kOffset.x_deg, 1e-9);
  EXPECT_NEAR(flip->zero.offset.y_deg, kOffset.y_deg, 1e-9);
  // Half the difference of the readings is the surface's tilt, to first order.
  EXPECT_NEAR(flip->surface_x_deg, kSurface.x_deg, 0.01);
  EXPECT_NEAR(flip->surface_y_deg, kSurface.y_deg, 0.01);
  EXPECT_EQ(flip->uri, "sim:0");
  const auto stored = readZeroOffset(dir / "calib.json");
  ASSERT_TRUE(stored && *stored);
  EXPECT_DOUBLE_EQ((*stored)->offset.x_deg, flip->zero.offset.x_deg);
  const auto document = readJsonFile((dir / "calib.json").string());
  ASSERT_TRUE(document);
  EXPECT_EQ((*document)["black_level_dn"], 64);
  EXPECT_EQ((*document)["inclinometer"]["method"], "flip");
  EXPECT_EQ((*document)["inclinometer"]["readings"].size(), 2u);
}

TEST(StoreFlipCalibration, AnImplausibleOffsetIsRefusedAndNothingIsStored) {
  TempDir dir;
  // Both readings say near level, but their mean vectors (which the offset is computed from) are
  // 30° off: saved files that disagree with themselves.
  TiltReading first = readingOf(kSurface), second = readingOf(kTurned);
  first.mean = second.mean = mountedGravity({30, 0}, {});
  const auto flip = storeFlipCalibration(dir / "calib.json", flipOf(first, second), "sim:0");
  ASSERT_FALSE(flip);
  EXPECT_EQ(flip.error().code, ErrorCode::kBadInput);
  EXPECT_NE(flip.error().message.find("beyond the plausible 10°"), std::string::npos)
      << flip.error().message;
  EXPECT_FALSE(fs::exists(dir / "calib.json"));
  // A reading far from level is refused before anything is computed.
  const auto tilted =
      storeFlipCalibration(dir / "calib.json", flipOf(readingOf({12, 0}), readingOf(kTurned)), "");
  ASSERT_FALSE(tilted);
  EXPECT_NE(tilted.error().message.find("within a few degrees of level"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "calib.json"));
}

// Two readings of the frame not turned (issue 18: an offset of 1.1992° was stored for the same
// position twice) agree; so do two of a turned frame on a level surface. Either way the flip
// cannot tell the mounting error from nothing, and refuses; a surface tilted just over
// kMinFlipSurfaceTiltDeg on one axis is enough.
TEST(StoreFlipCalibration, ReadingsThatShowNoTurnAreRefused) {
  TempDir dir;
  const auto unturned = storeFlipCalibration(
      dir / "calib.json", flipOf(readingOf(kSurface), readingOf(kSurface)), "sim:0");
  ASSERT_FALSE(unturned);
  EXPECT_EQ(unturned.error().code, ErrorCode::kBadInput);
  EXPECT_NE(unturned.error().message.find("the two readings agree (surface tilt x 0.000°"),
            std::string::npos)
      << unturned.error().message;
  EXPECT_FALSE(fs::exists(dir / "calib.json"));
  const auto level =
      storeFlipCalibration(dir / "calib.json", flipOf(readingOf({0, 0}), readingOf({0, 0})), "");
  ASSERT_FALSE(level);
  EXPECT_NE(level.error().message.find("a surface tilted at least 0.1°"), std::string::npos);
  const double just = 1.5 * kMinFlipSurfaceTiltDeg;
  const auto shimmed = storeFlipCalibration(
      dir / "calib.json", flipOf(readingOf({0, just}), readingOf({0, -just})), "");
  ASSERT_TRUE(shimmed) << shimmed.error().message;
  EXPECT_NEAR(shimmed->zero.offset.x_deg, kOffset.x_deg, 1e-9);
}

}  // namespace
}  // namespace glarecam::rig
