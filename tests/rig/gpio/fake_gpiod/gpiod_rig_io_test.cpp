// The libgpiod backend (rig/gpio/gpiod_rig_io.cpp) against a fake of libgpiod's C API
// (fake_gpiod.h): which lines it requests and how (consumer, direction, active-low, pull-up,
// initial level), what it writes and reads, its messages for lines out of range, unknown, busy or
// refused, and that every line it requested is released once, before its chip is closed, also
// when opening fails half-way.
#include <gpiod.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>

#include "fake_gpiod.h"
#include "rig/gpio/rig_io.h"

namespace glarecam::rig {
namespace {

using Log = std::vector<std::string>;

constexpr const char* kChipPath = "/dev/gpiochip0";

bool pressed(RigIo& io) {
  const Result<bool> level = io.buttonPressed();
  EXPECT_TRUE(level) << level.error().message;
  return level.value_or(false);
}

class GpiodRigIoFake : public ::testing::Test {
 protected:
  void SetUp() override {
    fake_gpiod::reset();
    fake_gpiod::addChip(kChipPath, "gpiochip0", "pinctrl-bcm2711", 58);
  }
  void TearDown() override {
    EXPECT_EQ(fake_gpiod::kernel().open_handles, 0) << "a chip handle was not closed";
    for (const std::string& entry : fake_gpiod::kernel().log) {
      EXPECT_FALSE(entry.starts_with("close releases")) << "released by close only: " << entry;
      EXPECT_FALSE(entry.starts_with("release of an unrequested")) << entry;
    }
  }

  static RigIoConfig config() {
    RigIoConfig config;
    config.chip = kChipPath;
    config.trigger = GpioLine{17u};
    config.led = GpioLine{std::string("GPIO27")};
    config.button = GpioLine{22u, true};
    return config;
  }
  static fake_gpiod::Line& line(unsigned offset) {
    return fake_gpiod::kernel().chips.at(kChipPath).lines.at(offset);
  }
  static Log& log() { return fake_gpiod::kernel().log; }
};

TEST_F(GpiodRigIoFake, RequestsTheConfiguredLinesAsGlarecam) {
  auto io = openGpiodRigIo(config());
  ASSERT_TRUE(io) << io.error().message;
  EXPECT_EQ((*io)->description(),
            "gpiochip0 [pinctrl-bcm2711]: trigger line 17, LED line 27 'GPIO27', button line 22 "
            "(active-low, pull-up)");
  EXPECT_TRUE((*io)->hasTrigger() && (*io)->hasLed() && (*io)->hasButton());
  EXPECT_EQ(log(), (Log{"request 17 glarecam", "request 27 glarecam", "request 22 glarecam"}));

  EXPECT_EQ(line(17).request_type, GPIOD_LINE_REQUEST_DIRECTION_OUTPUT);
  EXPECT_EQ(line(17).flags, 0);
  EXPECT_EQ(line(17).value, 0);  // requested inactive
  EXPECT_EQ(line(27).request_type, GPIOD_LINE_REQUEST_DIRECTION_OUTPUT);
  EXPECT_EQ(line(22).request_type, GPIOD_LINE_REQUEST_DIRECTION_INPUT);
  EXPECT_EQ(line(22).flags,
            GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW | GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP);
}

TEST_F(GpiodRigIoFake, WritesAndReadsTheLinesThenReleasesThemInactive) {
  {
    auto io = openGpiodRigIo(config());
    ASSERT_TRUE(io) << io.error().message;
    log().clear();
    ASSERT_TRUE((*io)->setLed(true));
    ASSERT_TRUE((*io)->pulseTrigger());
    line(22).value = 1;
    EXPECT_TRUE(pressed(**io));
    line(22).value = 0;
    EXPECT_FALSE(pressed(**io));
    EXPECT_EQ(log(), (Log{"set 27 1", "set 17 1", "set 17 0"}));
    log().clear();
  }
  // Outputs driven inactive, each line released once, then the chip closed.
  EXPECT_EQ(log(), (Log{"set 27 0", "set 17 0", "release 22", "release 27", "release 17",
                        "close gpiochip0"}));
}

TEST_F(GpiodRigIoFake, AbsentLinesAreNotRequestedAndTheirOperationsAreNoOps) {
  RigIoConfig only_led;
  only_led.chip = "pinctrl-bcm2711";  // by label
  only_led.led = GpioLine{5u, true};
  auto io = openGpiodRigIo(only_led);
  ASSERT_TRUE(io) << io.error().message;
  EXPECT_EQ((*io)->description(), "gpiochip0 [pinctrl-bcm2711]: LED line 5 (active-low)");
  EXPECT_FALSE((*io)->hasTrigger() || (*io)->hasButton());
  EXPECT_TRUE((*io)->pulseTrigger());
  EXPECT_FALSE(pressed(**io));
  EXPECT_EQ(line(5).flags, GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW);
  EXPECT_EQ(log(), (Log{"request 5 glarecam"}));
}

TEST_F(GpiodRigIoFake, OpensTheChipByNumberToo) {
  RigIoConfig by_number;
  by_number.chip = "0";
  auto io = openGpiodRigIo(by_number);
  ASSERT_TRUE(io) << io.error().message;
  EXPECT_EQ((*io)->description(), "gpiochip0 [pinctrl-bcm2711]: no lines");
}

TEST_F(GpiodRigIoFake, NamesAnOffsetBeyondTheChip) {
  RigIoConfig wrong = config();
  wrong.led = GpioLine{58u};
  const auto io = openGpiodRigIo(wrong);
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kHardware);
  EXPECT_EQ(io.error().message, "line 58 (LED) is beyond gpiochip0's 58 lines (0..57)");
  // What was requested before the failure is driven inactive and released, then the chip closed.
  EXPECT_EQ(log(), (Log{"request 17 glarecam", "set 17 0", "release 17", "close gpiochip0"}));
}

TEST_F(GpiodRigIoFake, NamesALineNameNotFound) {
  RigIoConfig wrong = config();
  wrong.button = GpioLine{std::string("BUTTON"), true};
  const auto io = openGpiodRigIo(wrong);
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().message,
            "line 'BUTTON' (button) not found on gpiochip0 (`gpioinfo gpiochip0` lists the line "
            "names)");
}

TEST_F(GpiodRigIoFake, NamesTheUserOfABusyLine) {
  line(27).other_consumer = "gpio-leds";
  RigIoConfig busy = config();
  busy.led = GpioLine{27u};
  const auto io = openGpiodRigIo(busy);
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kHardware);
  EXPECT_EQ(io.error().message, "line 27 (LED) of gpiochip0 is used by gpio-leds");
  EXPECT_EQ(log(), (Log{"request 17 glarecam", "set 17 0", "release 17", "close gpiochip0"}));
}

TEST_F(GpiodRigIoFake, RefusesOneLineInTwoRoles) {
  RigIoConfig twice = config();
  twice.led = GpioLine{std::string("GPIO17")};  // the trigger's offset, by name
  const auto io = openGpiodRigIo(twice);
  ASSERT_FALSE(io);
  EXPECT_EQ(io.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(io.error().message,
            "line 17 'GPIO17' (LED) of gpiochip0 is also configured as line 17 (trigger)");
}

TEST_F(GpiodRigIoFake, ExplainsARefusedPullUp) {
  line(22).request_errno = EINVAL;
  const auto io = openGpiodRigIo(config());
  ASSERT_FALSE(io);
  EXPECT_TRUE(io.error().message.starts_with(
      "line 22 (button) of gpiochip0: the kernel refused the pull-up (Invalid argument)"))
      << io.error().message;
  EXPECT_NE(io.error().message.find("button_pull_up = false"), std::string::npos);
}

TEST_F(GpiodRigIoFake, ExplainsAPermissionDenied) {
  fake_gpiod::kernel().open_errno = EACCES;
  const auto io = openGpiodRigIo(config());
  ASSERT_FALSE(io);
  EXPECT_TRUE(io.error().message.starts_with(
      "GPIO chip /dev/gpiochip0: permission denied: add the user to the gpio group"))
      << io.error().message;
}

TEST_F(GpiodRigIoFake, NamesTheLineWhenAWriteOrReadFails) {
  auto io = openGpiodRigIo(config());
  ASSERT_TRUE(io) << io.error().message;
  line(27).io_errno = EIO;
  const Status led = (*io)->setLed(true);
  ASSERT_FALSE(led);
  EXPECT_EQ(led.error().message,
            "line 27 'GPIO27' (LED) of gpiochip0: cannot set to active: Input/output error");
  line(22).io_errno = EIO;
  const Result<bool> button = (*io)->buttonPressed();
  ASSERT_FALSE(button);
  EXPECT_EQ(button.error().message,
            "line 22 (button) of gpiochip0: cannot read: Input/output error");
  line(17).io_errno = EIO;
  EXPECT_FALSE((*io)->pulseTrigger());
  line(27).io_errno = 0;
  line(17).io_errno = 0;
}

}  // namespace
}  // namespace glarecam::rig
