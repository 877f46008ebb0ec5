// GPIO by chip name: the simulated chip ("sim") checks lines as a Raspberry Pi 4's gpiochip0
// would, and its scripted presses must outlast the debounce.
#include "rig/gpio/rig_io_registry.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

namespace glarecam::rig {
namespace {

// The simulated chip checks lines as a Raspberry Pi 4's gpiochip0 would (58 lines, GPIOn).
TEST(SimChip, ChecksLinesLikeARealChip) {
  RigIoConfig config;
  config.chip = "sim";
  config.led = GpioLine{17u, false};
  config.trigger = GpioLine{std::string("GPIO22"), false};
  ASSERT_TRUE(openRigIo(config));
  config.trigger = GpioLine{std::string("GPIO17"), false};  // the LED's line by name
  EXPECT_EQ(openRigIo(config).error().code, ErrorCode::kBadInput);
  config.trigger = GpioLine{58u, false};
  const auto beyond = openRigIo(config);
  ASSERT_FALSE(beyond);
  EXPECT_NE(beyond.error().message.find("beyond the simulated chip's 58 lines"), std::string::npos);
  config.trigger = GpioLine{std::string("GPIO022"), false};  // no such name on a real chip
  EXPECT_FALSE(openRigIo(config));
  config.trigger = GpioLine{std::string("STATUS"), false};
  EXPECT_NE(openRigIo(config).error().message.find("'STATUS' (trigger) not found"),
            std::string::npos);
}

TEST(SimChip, ScriptedPressesOutlastTheDebounce) {
  RigIoConfig config;
  config.chip = "sim:button_period_s=0.5";
  config.button = GpioLine{27u, true};
  config.debounce = std::chrono::milliseconds(300);  // presses of 600 ms do not fit in 0.5 s
  const auto refused = openRigIo(config);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("too short for debounce_ms = 300"), std::string::npos);
  config.chip = "sim:button_period_s=2";
  EXPECT_TRUE(openRigIo(config));
  config.chip = "sim:wobble=1";
  EXPECT_EQ(openRigIo(config).error().code, ErrorCode::kBadInput);
}

}  // namespace
}  // namespace glarecam::rig
