// The libgpiod backend against the real library on a machine without GPIO chips (absent chips,
// files that are no chip, a bad config), a real chip when there is one, and the message of a
// build without libgpiod. Its logic against a fake of libgpiod is in
// tests/rig/gpiod_rig_io_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/build_config.h"
#include "rig/gpio/gpio_errors.h"
#include "rig/gpio/gpio_test_support.h"
#include "rig/gpio/rig_io.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

using namespace std::chrono_literals;
using testing::allLines;

#if GLARECAM_WITH_GPIOD

// Messages list the machine's chips: exact only where there are none.
bool machineHasGpioChips() { return !presentGpioChips().empty(); }

TEST(GpiodRigIo, AnAbsentChipIsNamed) {
  if (std::filesystem::exists("/dev/gpiochip0")) GTEST_SKIP() << "this machine has gpiochip0";
  const auto io = openGpiodRigIo(allLines());
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kHardware);
  if (!machineHasGpioChips()) {
    EXPECT_EQ(io.error().message, "GPIO chip gpiochip0 not found (/dev/gpiochip* present: none)");
  }
  for (const char* chip : {"/dev/gpiochip0", "0", "no-such-label"}) {
    RigIoConfig config = allLines();
    config.chip = chip;
    const auto absent = openGpiodRigIo(config);
    ASSERT_FALSE(absent) << chip;
    EXPECT_EQ(absent.error().code, ErrorCode::kHardware);
    EXPECT_TRUE(absent.error().message.starts_with("GPIO chip " + std::string(chip) +
                                                   " not found (/dev/gpiochip* present: "))
        << absent.error().message;
  }
}

TEST(GpiodRigIo, AFileThatIsNoChipIsRefused) {
  testing::TempDir directory;
  const std::filesystem::path file = directory.path() / "gpiochip0";
  std::ofstream(file) << "not a chip\n";
  for (const std::string& chip :
       {std::string("/dev/null"), file.string(), directory.path().string()}) {
    RigIoConfig config = allLines();
    config.chip = chip;
    const auto io = openGpiodRigIo(config);
    ASSERT_FALSE(io) << chip;
    EXPECT_EQ(io.error().code, ErrorCode::kHardware);
    EXPECT_TRUE(io.error().message.starts_with(chip + " is not a GPIO chip ("))
        << io.error().message;
  }
}

TEST(GpiodRigIo, AnInvalidConfigFailsBeforeTouchingTheHardware) {
  RigIoConfig config = allLines();
  config.trigger_pulse = 0us;
  const auto io = openGpiodRigIo(config);
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kBadInput);
}

TEST(GpiodRigIo, OnDeviceOpensARealChip) {
  if (!std::filesystem::exists("/dev/gpiochip0")) GTEST_SKIP() << "no /dev/gpiochip0 here";
  RigIoConfig config;  // no lines: opening the chip claims nothing
  const auto io = openGpiodRigIo(config);
  ASSERT_TRUE(io) << io.error().message;
  EXPECT_TRUE((*io)->description().starts_with("gpiochip0 ["));
  EXPECT_FALSE((*io)->hasLed());
  EXPECT_TRUE((*io)->setLed(true));
}

#else

TEST(GpiodRigIo, SaysItWasBuiltWithoutLibgpiod) {
  const auto io = openGpiodRigIo(allLines());
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kHardware);
  EXPECT_NE(io.error().message.find("glarecam was built without libgpiod"), std::string::npos);
}

#endif

}  // namespace
}  // namespace glarecam::rig
