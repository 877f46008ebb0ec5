// The GPIO config: each field validated with a message naming it, and lines described.
#include "rig/gpio/rig_io.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "rig/gpio/gpio_test_support.h"

namespace glarecam::rig {
namespace {

using namespace std::chrono_literals;
using testing::allLines;

TEST(RigIoConfig, ValidatesItsFields) {
  EXPECT_TRUE(RigIoConfig{}.validate());
  EXPECT_TRUE(allLines().validate());

  const auto problem = [](const RigIoConfig& config) {
    const Status status = config.validate();
    EXPECT_FALSE(status);
    if (status) return std::string();
    EXPECT_EQ(status.error().code, ErrorCode::kBadInput);
    return status.error().message;
  };
  RigIoConfig config = allLines();
  config.chip = "";
  EXPECT_EQ(problem(config), "GPIO chip: empty (a name such as gpiochip0, a path or label)");

  config = allLines();
  config.led = GpioLine{std::string()};
  EXPECT_EQ(problem(config), "GPIO LED line: empty name (give an offset or a name from gpioinfo)");

  config = allLines();
  config.button = GpioLine{17u, true};
  EXPECT_EQ(problem(config), "GPIO trigger and button are the same line 17, active-low");
  config = allLines();
  config.led = GpioLine{std::string("BUTTON")};
  EXPECT_EQ(problem(config), "GPIO LED and button are the same line 'BUTTON', active-low");

  config = allLines();
  config.debounce = -1ms;
  EXPECT_EQ(problem(config), "GPIO button debounce -1 ms: outside 0..1000 ms");
  config.debounce = 1001ms;
  EXPECT_EQ(problem(config), "GPIO button debounce 1001 ms: outside 0..1000 ms");
  config.debounce = 0ms;
  EXPECT_TRUE(config.validate());

  config.trigger_pulse = 0us;
  EXPECT_EQ(problem(config), "GPIO trigger pulse 0 us: outside 1..100000 us");
  config.trigger_pulse = 100'001us;
  EXPECT_EQ(problem(config), "GPIO trigger pulse 100001 us: outside 1..100000 us");
}

TEST(RigIoConfig, DescribesLines) {
  EXPECT_EQ(describeGpioLine(GpioLine{17u}), "line 17");
  EXPECT_EQ(describeGpioLine(GpioLine{std::string("STATUS_LED"), true}),
            "line 'STATUS_LED', active-low");
}

TEST(RigIoConfig, APulledUpButtonMustBeActiveLow) {
  RigIoConfig config;
  config.button = GpioLine{22u, false};  // the pull-up holds it high: it would read pressed
  const Status refused = config.validate();
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("button_active_low = true"), std::string::npos);
  config.button->active_low = true;
  EXPECT_TRUE(config.validate());
  config.button->active_low = false;
  config.button_pull_up = false;  // an external pull-down, a button to 3.3 V
  EXPECT_TRUE(config.validate());
}

}  // namespace
}  // namespace glarecam::rig
