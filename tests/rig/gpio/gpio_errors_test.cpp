// The GPIO backend's messages: the chip and line named, what to do, and the chips present.
#include "rig/gpio/gpio_errors.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <fstream>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace glarecam::rig {
namespace {

TEST(GpioErrors, NameTheChipAndLineAndSayWhatToDo) {
  EXPECT_EQ(gpioChipOpenError("gpiochip0", ENOENT, {}).message,
            "GPIO chip gpiochip0 not found (/dev/gpiochip* present: none)");
  EXPECT_EQ(
      gpioChipOpenError("gpiochip4", ENOENT, {"gpiochip0 [pinctrl-bcm2711]", "gpiochip1"}).message,
      "GPIO chip gpiochip4 not found (/dev/gpiochip* present: gpiochip0 [pinctrl-bcm2711], "
      "gpiochip1)");
  EXPECT_EQ(gpioChipOpenError("/dev/null", ENOTTY, {}).message,
            "/dev/null is not a GPIO chip (/dev/gpiochip* present: none)");
  const Error denied = gpioChipOpenError("gpiochip0", EACCES, {});
  EXPECT_EQ(denied.code, ErrorCode::kHardware);
  EXPECT_NE(denied.message.find("permission denied"), std::string::npos);
  EXPECT_NE(denied.message.find("gpio group"), std::string::npos);
  EXPECT_NE(denied.message.find("udev rule"), std::string::npos);

  EXPECT_EQ(gpioLineRequestError("gpiochip0", "line 17 (LED)", EBUSY, "gpio-leds").message,
            "line 17 (LED) of gpiochip0 is used by gpio-leds");
  EXPECT_EQ(gpioLineRequestError("gpiochip0", "line 17 (LED)", EBUSY, "").message,
            "line 17 (LED) of gpiochip0 is used by another program or a kernel driver");
  EXPECT_NE(
      gpioLineRequestError("gpiochip0", "line 22 (button)", EPERM, "").message.find("gpio group"),
      std::string::npos);
  const std::string bias =
      gpioLineRequestError("gpiochip0", "line 22 (button)", EINVAL, "", true).message;
  EXPECT_NE(bias.find("button_pull_up = false"), std::string::npos) << bias;
  EXPECT_EQ(gpioLineRequestError("gpiochip0", "line 22 (button)", EINVAL, "", false).message,
            "line 22 (button) of gpiochip0: Invalid argument");
}

TEST(GpioErrors, ListsPresentChipsSorted) {
  testing::TempDir dev;
  for (const char* name : {"gpiochip1", "ttyS0", "gpiochip0"}) std::ofstream(dev.path() / name);
  EXPECT_EQ(presentGpioChips(dev.path()), (std::vector<std::string>{"gpiochip0", "gpiochip1"}));
  EXPECT_TRUE(presentGpioChips(dev.path() / "absent").empty());
}

}  // namespace
}  // namespace glarecam::rig
