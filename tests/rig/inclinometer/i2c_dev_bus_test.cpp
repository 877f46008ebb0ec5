// The real i2c-dev bus on a machine without I2C: an absent bus, nodes that are not buses, and a
// node the user may not open, each a clear error.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>

#include "rig/inclinometer/adxl355.h"
#include "rig/inclinometer/adxl355_test_support.h"
#include "rig/inclinometer/i2c_bus.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

namespace fs = std::filesystem;
using testing::contains;
using testing::kAddress;
using testing::TempDir;
using testing::writeFile;

TEST(I2cDevBus, AbsentBusExplainsHowToEnableI2c) {
  if (fs::exists("/dev/i2c-1")) GTEST_SKIP() << "this machine has /dev/i2c-1";
  const auto bus = openI2cDevBus("/dev/i2c-1");
  ASSERT_FALSE(bus);
  EXPECT_EQ(bus.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(bus.error().message, "/dev/i2c-1: no such I2C bus")) << bus.error().message;
  EXPECT_TRUE(contains(bus.error().message, "dtparam=i2c_arm=on")) << bus.error().message;
  EXPECT_TRUE(contains(bus.error().message, "i2c-dev")) << bus.error().message;
}

TEST(I2cDevBus, ARegularFileIsNotABus) {
  TempDir dir;
  const fs::path file = dir.path() / "i2c-9";
  writeFile(file, "not a bus");
  auto bus = openI2cDevBus(file.string());
  ASSERT_TRUE(bus) << bus.error().message;  // open(2) cannot tell; the first transfer can
  const std::array<std::uint8_t, 1> pointer{0x00};
  std::array<std::uint8_t, 1> value{};
  const auto status = (*bus)->transfer(kAddress, pointer, value);
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(status.error().message, file.string() + " is not an I2C bus"))
      << status.error().message;

  // The driver reports the same when opened over it.
  auto again = openI2cDevBus(file.string());
  ASSERT_TRUE(again);
  const auto opened = openAdxl355(std::move(*again), kAddress, {}, "adxl355:" + file.string());
  ASSERT_FALSE(opened);
  EXPECT_TRUE(contains(opened.error().message, "is not an I2C bus")) << opened.error().message;
}

TEST(I2cDevBus, DevNullIsNotABus) {
  auto bus = openI2cDevBus("/dev/null");
  ASSERT_TRUE(bus) << bus.error().message;
  EXPECT_EQ((*bus)->name(), "/dev/null");
  const std::array<std::uint8_t, 2> write{adxl355::kRegReset, adxl355::kResetCode};
  const auto status = (*bus)->transfer(kAddress, write, {});
  ASSERT_FALSE(status);
  EXPECT_TRUE(contains(status.error().message, "/dev/null is not an I2C bus"))
      << status.error().message;
}

TEST(I2cDevBus, UnreadableNodeGivesAPermissionHint) {
  if (::geteuid() == 0) GTEST_SKIP() << "root opens any file: no EACCES to provoke";
  TempDir dir;
  const fs::path file = dir.path() / "i2c-8";
  writeFile(file, "");
  fs::permissions(file, fs::perms::none);
  const auto bus = openI2cDevBus(file.string());
  ASSERT_FALSE(bus);
  EXPECT_EQ(bus.error().code, ErrorCode::kHardware);
  EXPECT_TRUE(contains(bus.error().message, "permission denied")) << bus.error().message;
  EXPECT_TRUE(contains(bus.error().message, "i2c")) << bus.error().message;
}

}  // namespace
}  // namespace glarecam::rig
