// The inclinometer's block in the rig's calibration file: the zero offset merged into an existing
// file and read back, bad files named and never overwritten, and a tilt reading's JSON.
#include "rig/inclinometer/zero_offset_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/json.h"
#include "rig/inclinometer/scripted_inclinometer.h"
#include "rig/rig_config_test_support.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

using testing::noisySamples;
using testing::ScriptedInclinometer;
using testing::TempDir;
using testing::writeText;

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
                "str.json: inclinometer.zero_offset_x_deg must be a number, not \"0.3\""),
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

}  // namespace
}  // namespace glarecam::rig
