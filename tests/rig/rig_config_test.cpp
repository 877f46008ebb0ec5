// The rig's sections of the TOML config: every section read, defaults, and each bad config named
// by file, line and problem.
#include "rig/rig_config.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <variant>

#include "rig/rig_config_test_support.h"
#include "sun/solar_position.h"
#include "support/test_support.h"

namespace glarecam::rig {
namespace {

using testing::kSunConfig;
using testing::readRigConfig;
using testing::TempDir;
using testing::writeText;

struct BadConfig {
  const char* text;
  const char* message;  // the error must contain this
};

TEST(RigConfig, ReadsEverySection) {
  TempDir dir;
  const auto config = readRigConfig(writeText(dir, "rig.toml", kSunConfig));
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(config->site);
  EXPECT_DOUBLE_EQ(config->site->latitude_deg, 39.742476);
  EXPECT_DOUBLE_EQ(config->site->pressure_hpa, 820);
  EXPECT_EQ(*config->calibration, dir / "calib.json");  // relative to the config file
  EXPECT_EQ(config->inclinometer->uri, "sim:30");
  EXPECT_EQ(config->inclinometer->tilt.samples, 20);
  EXPECT_DOUBLE_EQ(*config->module_azimuth_deg, 180);
  EXPECT_FALSE(config->fixed_source);
}

TEST(RigConfig, PressureDefaultsToTheStandardAtmosphere) {
  // ISO 2533: 1013.25 hPa at sea level, 898.7 hPa at 1000 m, 795.0 hPa at 2000 m (tabulated to
  // 0.1 hPa).
  EXPECT_NEAR(sun::standardPressureHpa(0), 1013.25, 1e-9);
  EXPECT_NEAR(sun::standardPressureHpa(1000), 898.75, 0.1);
  EXPECT_NEAR(sun::standardPressureHpa(2000), 795.01, 0.1);
  TempDir dir;
  const auto config =
      readRigConfig(writeText(dir, "rig.toml",
                              "[site]\nlatitude_deg = 1\nlongitude_deg = 2\naltitude_m = 1000\n"
                              "[module]\nazimuth_deg = 0\ntilt_deg = 10\n"));
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_NEAR(config->site->pressure_hpa, 898.75, 0.1);
}

TEST(RigConfig, BadConfigsNameTheFileLineAndProblem) {
  const BadConfig cases[] = {
      {"[site]\nlatitude_deg = 91\nlongitude_deg = 0\n",
       "rig.toml:2: site.latitude_deg = 91 is outside [-90, 90]"},
      {"[site]\nlatitude_deg = \"north\"\nlongitude_deg = 0\n",
       "rig.toml:2: site.latitude_deg must be a number"},
      {"[site]\nlongitude_deg = 0\n", "rig.toml:1: [site] needs latitude_deg"},
      {"[site]\nlatitude_deg = 1\nlongitude_deg = 0\nlattitude = 3\n",
       "rig.toml:4: unknown key site.lattitude"},
      {"[sight]\nx = 1\n", "rig.toml:1: unknown section [sight]"},
      {"[site]\nlatitude_deg = 1\nlongitude_deg = 0\n[source]\nelevation_deg = 0\nazimuth_deg = 0\n"
       "[module]\nazimuth_deg = 0\n",
       "not both"},
      {"[site]\nlatitude_deg = 1\nlongitude_deg = 0\n", "[module] azimuth_deg is needed"},
      {"[inclinometer]\nsamples = 5\n", "[inclinometer] needs uri"},
      {"[inclinometer]\nuri = \"sim:0\"\nsamples = 1\n",
       "rig.toml:3: inclinometer.samples = 1 is outside"},
      {"[site\nlatitude_deg = 1\n", "rig.toml:1:"},
      {"camera = 5\n", "rig.toml:1: camera must be a non-empty string"},
      {"[site]\nlatitude_deg = nan\nlongitude_deg = 0\n", "site.latitude_deg must be a number"},
  };
  for (const BadConfig& c : cases) {
    TempDir dir;
    const auto config = readRigConfig(writeText(dir, "rig.toml", c.text));
    ASSERT_FALSE(config) << c.text;
    EXPECT_EQ(config.error().code, ErrorCode::kBadInput);
    EXPECT_NE(config.error().message.find(c.message), std::string::npos)
        << "got: " << config.error().message << "\nwant: " << c.message;
    EXPECT_EQ(config.error().message.find('\n'), std::string::npos) << config.error().message;
  }
  const auto missing = readRigConfig("/nonexistent/rig.toml");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("/nonexistent/rig.toml: no such file"), std::string::npos);
}

// A lab lamp's illuminance at the module, measured once with an illuminance meter: a number of
// lx or "LX±U", origin given; a bad one names the file, line and key.
TEST(RigConfig, ALabLampStatesItsIlluminance) {
  const std::string lamp = "[source]\nelevation_deg = 0\nazimuth_deg = 180\n";
  const std::string rest = "[module]\nazimuth_deg = 180\ntilt_deg = 50\n";
  TempDir dir;
  auto config =
      readRigConfig(writeText(dir, "rig.toml", lamp + "illuminance = \"92500±2800\"\n" + rest));
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(config->fixed_source_illuminance);
  EXPECT_EQ(config->fixed_source_illuminance->illuminance_lx, 92'500);
  EXPECT_EQ(config->fixed_source_illuminance->illuminance_u_lx, 2'800);
  EXPECT_EQ(config->fixed_source_illuminance->origin, IlluminanceOrigin::kGiven);
  config = readRigConfig(writeText(dir, "rig.toml", lamp + "illuminance = 40000\n" + rest));
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->fixed_source_illuminance->illuminance_lx, 40'000);
  config = readRigConfig(writeText(dir, "rig.toml", lamp + rest));
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_FALSE(config->fixed_source_illuminance);
  for (const char* bad : {"0", "-3", "nan", "2e5", "\"bright\"", "true", "\"9e4±9e4\""}) {
    const auto refused =
        readRigConfig(writeText(dir, "rig.toml", lamp + "illuminance = " + bad + "\n" + rest));
    ASSERT_FALSE(refused) << bad;
    EXPECT_EQ(refused.error().code, ErrorCode::kBadInput);
    EXPECT_NE(refused.error().message.find("rig.toml:4: "), std::string::npos)
        << refused.error().message;
    EXPECT_NE(refused.error().message.find("source.illuminance"), std::string::npos)
        << refused.error().message;
  }
}

TEST(RigConfig, ReadsTheGpioLines) {
  TempDir dir;
  const auto config = readRigConfig(writeText(dir, "rig.toml", R"([gpio]
chip = "pinctrl-bcm2711"
led = 17
trigger = "GPIO22"
trigger_active_low = true
button = 27
button_active_low = true
button_pull_up = false
debounce_ms = 30
trigger_pulse_us = 500
)"));
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(config->gpio);
  EXPECT_EQ(config->gpio->chip, "pinctrl-bcm2711");
  EXPECT_EQ(std::get<unsigned>(config->gpio->led->line), 17u);
  EXPECT_FALSE(config->gpio->led->active_low);
  EXPECT_EQ(std::get<std::string>(config->gpio->trigger->line), "GPIO22");
  EXPECT_TRUE(config->gpio->trigger->active_low);
  EXPECT_TRUE(config->gpio->button->active_low);
  EXPECT_FALSE(config->gpio->button_pull_up);
  EXPECT_EQ(config->gpio->debounce, std::chrono::milliseconds(30));
  EXPECT_EQ(config->gpio->trigger_pulse, std::chrono::microseconds(500));
}

TEST(RigConfig, AButtonOnThePullUpIsActiveLowByDefault) {
  TempDir dir;
  const auto pulled = readRigConfig(writeText(dir, "a.toml", "[gpio]\nbutton = 22\n"));
  ASSERT_TRUE(pulled) << pulled.error().message;
  EXPECT_TRUE(pulled->gpio->button->active_low);
  const auto external =
      readRigConfig(writeText(dir, "b.toml", "[gpio]\nbutton = 22\nbutton_pull_up = false\n"));
  ASSERT_TRUE(external) << external.error().message;
  EXPECT_FALSE(external->gpio->button->active_low);
}

TEST(RigConfig, BadGpioLinesNameTheLine) {
  const BadConfig cases[] = {
      {"[gpio]\nled = 1.5\n", "rig.toml:2: gpio.led must be a line offset"},
      {"[gpio]\nled = \"\"\n", "rig.toml:2: gpio.led must be a line offset"},
      {"[gpio]\nled = 3\nled_active_low = 1\n",
       "rig.toml:3: gpio.led_active_low must be true or false"},
      {"[gpio]\nbuton = 3\n", "rig.toml:2: unknown key gpio.buton"},
      {"[gpio]\nled = 3\nbutton = 3\n", "rig.toml:1: [gpio]"},
      {"[gpio]\ndebounce_ms = 5000\n", "gpio.debounce_ms = 5000 is outside [0, 1000]"},
      {"[gpio]\ntrigger_pulse_us = 0\n", "gpio.trigger_pulse_us = 0 is outside"},
  };
  for (const BadConfig& c : cases) {
    TempDir dir;
    const auto config = readRigConfig(writeText(dir, "rig.toml", c.text));
    ASSERT_FALSE(config) << c.text;
    EXPECT_NE(config.error().message.find(c.message), std::string::npos)
        << "got: " << config.error().message << "\nwant: " << c.message;
  }
}

}  // namespace
}  // namespace glarecam::rig
