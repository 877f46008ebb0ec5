// The IIO inclinometer backend over a fake sysfs tree: scales and offsets as the ABI defines them,
// the temperature, and bad or missing files named.
#include "rig/inclinometer/iio_inclinometer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "rig/inclinometer/adxl355_test_support.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

namespace fs = std::filesystem;
using testing::contains;
using testing::TempDir;
using testing::writeFile;

// A fake /sys/bus/iio/devices with one accelerometer, iio:device0, 1 g along +Z.
class FakeSysfs {
 public:
  FakeSysfs() {
    set("name", "adxl355\n");
    set("in_accel_x_raw", "0\n");
    set("in_accel_y_raw", "0\n");
    set("in_accel_z_raw", "1000\n");
    set("in_accel_scale", "0.00980665\n");  // 1 mg per LSB, in m/s²
  }
  fs::path root() const { return dir_.path(); }
  fs::path device() const { return dir_.path() / "iio:device0"; }
  void set(const std::string& file, const std::string& text) { writeFile(device() / file, text); }
  void remove(const std::string& file) { fs::remove(device() / file); }

  Result<std::unique_ptr<Inclinometer>> open() const {
    return openIioInclinometer("iio:device0", root());
  }
  Result<AccelerationSample> read() const {
    std::unique_ptr<Inclinometer> inclinometer;
    GLARECAM_ASSIGN(inclinometer, open());
    return inclinometer->read();
  }

 private:
  TempDir dir_;
};

// Two roundings in double ((raw + offset) × scale, then ÷ 9.80665): a few ulps of 1 g.
constexpr double kIioTolerance_g = 1e-12;

TEST(IioInclinometer, ReadsTheSharedScale) {
  FakeSysfs sysfs;
  sysfs.set("in_accel_x_raw", "-500\n");
  sysfs.set("in_accel_sampling_frequency", "100.000000\n");
  const auto inclinometer = sysfs.open();
  ASSERT_TRUE(inclinometer) << inclinometer.error().message;
  const auto& info = (*inclinometer)->info();
  EXPECT_EQ(info.uri, "iio:iio:device0");
  EXPECT_EQ(info.backend, "iio");
  EXPECT_EQ(info.model, "adxl355");
  EXPECT_EQ(info.full_scale_g, 0.0);
  EXPECT_TRUE(contains(info.detail, "sampling frequency 100")) << info.detail;
  EXPECT_TRUE(contains(info.detail, "scale 0.00980665 m/s² per LSB")) << info.detail;

  const auto sample = (*inclinometer)->read();
  ASSERT_TRUE(sample) << sample.error().message;
  EXPECT_NEAR(sample->x_g, -0.5, kIioTolerance_g);
  EXPECT_NEAR(sample->y_g, 0.0, kIioTolerance_g);
  EXPECT_NEAR(sample->z_g, 1.0, kIioTolerance_g);
  EXPECT_FALSE(sample->temperature_c);  // no in_temp_* files

  // Successive reads are fresh reads of the files.
  sysfs.set("in_accel_y_raw", "250");
  const auto next = (*inclinometer)->read();
  ASSERT_TRUE(next);
  EXPECT_NEAR(next->y_g, 0.25, kIioTolerance_g);
}

TEST(IioInclinometer, PerAxisScaleAndOffsetsFollowTheAbi) {
  FakeSysfs sysfs;
  sysfs.set("in_accel_x_raw", "90");
  sysfs.set("in_accel_x_offset", "10");        // (90 + 10) × scale
  sysfs.set("in_accel_x_scale", "0.0196133");  // 2 mg per LSB on X only
  sysfs.set("in_accel_offset", "-1000");       // shared: Y and Z
  sysfs.set("in_accel_y_raw", "1500");
  sysfs.set("in_accel_z_raw", "1000");
  const auto sample = sysfs.read();
  ASSERT_TRUE(sample) << sample.error().message;
  EXPECT_NEAR(sample->x_g, 0.2, kIioTolerance_g);
  EXPECT_NEAR(sample->y_g, 0.5, kIioTolerance_g);
  EXPECT_NEAR(sample->z_g, 0.0, kIioTolerance_g);
}

TEST(IioInclinometer, ReadsTheTemperatureInMilliDegrees) {
  FakeSysfs sysfs;
  sysfs.set("in_temp_raw", "1885");
  sysfs.set("in_temp_offset", "-2111.25");  // the Linux adxl355 driver's values
  sysfs.set("in_temp_scale", "-110.497238");
  auto sample = sysfs.read();
  ASSERT_TRUE(sample) << sample.error().message;
  ASSERT_TRUE(sample->temperature_c);
  // (1885 − 2111.25) × −110.497238 m°C = 25.0 °C up to the driver's 6-digit scale: 1e-5 °C.
  EXPECT_NEAR(*sample->temperature_c, 25.0, 1e-5);

  sysfs.set("in_temp_input", "21500");  // a processed value wins
  sample = sysfs.read();
  ASSERT_TRUE(sample && sample->temperature_c);
  EXPECT_EQ(*sample->temperature_c, 21.5);

  sysfs.set("in_temp_input", "nan");
  sample = sysfs.read();
  ASSERT_FALSE(sample);
  EXPECT_TRUE(contains(sample.error().message, "in_temp_input: not a finite number"));
}

TEST(IioInclinometer, AbsentDeviceListsThePresentOnes) {
  FakeSysfs sysfs;
  fs::create_directories(sysfs.root() / "iio:device1");
  fs::create_directories(sysfs.root() / "trigger0");
  const auto opened = openIioInclinometer("iio:device3", sysfs.root());
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kHardware);
  EXPECT_EQ(opened.error().message, "no IIO device iio:device3 under " + sysfs.root().string() +
                                        " (devices present: iio:device0, iio:device1)");

  TempDir empty;
  const auto none = openIioInclinometer("iio:device0", empty.path() / "absent");
  ASSERT_FALSE(none);
  EXPECT_TRUE(contains(none.error().message, "(no devices present)")) << none.error().message;

  EXPECT_EQ(openIioInclinometer("../etc", sysfs.root()).error().code, ErrorCode::kBadInput);
}

TEST(IioInclinometer, ADeviceWithoutAccelChannelsIsNotAnAccelerometer) {
  FakeSysfs sysfs;
  sysfs.set("name", "bmp280");
  sysfs.remove("in_accel_x_raw");
  const auto opened = sysfs.open();
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(opened.error().message, "iio:device0 (bmp280) is not an accelerometer: no "))
      << opened.error().message;
  EXPECT_TRUE(contains(opened.error().message, "in_accel_x_raw")) << opened.error().message;
}

TEST(IioInclinometer, BadFilesAreErrorsNamingTheFile) {
  struct Case {
    std::string file, text, expected;
  };
  const std::vector<Case> cases{
      {"in_accel_x_raw", "nan\n", "in_accel_x_raw: not a finite number: 'nan'"},
      {"in_accel_y_raw", "", "in_accel_y_raw: empty"},
      {"in_accel_z_raw", "12abc", "in_accel_z_raw: not a number: '12abc'"},
      {"in_accel_scale", "inf", "in_accel_scale: not a finite number: 'inf'"},
      {"in_accel_scale", "\n", "in_accel_scale: empty"},
      {"in_accel_x_offset", "-", "in_accel_x_offset: not a number: '-'"},
  };
  for (const auto& [file, text, expected] : cases) {
    FakeSysfs sysfs;
    sysfs.set(file, text);
    const auto sample = sysfs.read();
    ASSERT_FALSE(sample) << file << " = '" << text << "'";
    EXPECT_EQ(sample.error().code, ErrorCode::kHardware);
    EXPECT_TRUE(contains(sample.error().message, expected)) << sample.error().message;
    EXPECT_TRUE(contains(sample.error().message, sysfs.device().string()))
        << sample.error().message;
  }
}

TEST(IioInclinometer, MissingScaleOrAllZeroIsAnError) {
  FakeSysfs sysfs;
  sysfs.remove("in_accel_scale");
  auto sample = sysfs.read();
  ASSERT_FALSE(sample);
  EXPECT_TRUE(contains(sample.error().message, "in_accel_scale: missing"))
      << sample.error().message;

  FakeSysfs zero;
  zero.set("in_accel_z_raw", "0");
  sample = zero.read();
  ASSERT_FALSE(sample);
  EXPECT_TRUE(contains(sample.error().message, "all read exactly 0")) << sample.error().message;
}

}  // namespace
}  // namespace glarecam::rig
