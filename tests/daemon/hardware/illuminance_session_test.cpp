// The illuminance instrument in glarecamd (daemon/hardware/illuminance_session.h): the simulated
// instrument served on loopback and read through the libmodbus backend during each bracket, its
// source recorded in the stack; an instrument that fails leaves the stacks unreferred, never
// wrong; the simulated sun's E follows the time lapse.
#include "daemon/hardware/illuminance_session.h"

#include <gtest/gtest.h>

#include "core/build_config.h"
#include "daemon/daemon_fixture.h"
#include "daemon/hardware/rig_doctor.h"
#include "daemon/hardware/simulated_rig.h"
#include "sun/clear_sky.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;
using testing::utc;

constexpr const char* kSimInstrument = R"([illuminance]
transport = "sim"
data_type = "float32"
units = "W/m2"
uncertainty_pct = 2
sample_interval_ms = 5
)";

const sun::SiteLocation kSimulatedSite{.latitude_deg = kSimulatedLatitudeDeg,
                                       .longitude_deg = kSimulatedLongitudeDeg,
                                       .altitude_m = 278,
                                       .pressure_hpa = sun::standardPressureHpa(278)};

TEST(SimulatedSourceIlluminanceTest, IsTheClearSkySunOfTheTime) {
  const UtcTime noon = utc("2026-06-21T11:30:00Z");
  const auto lx = simulatedSourceIlluminance(noon, kSimulatedSite);
  ASSERT_TRUE(lx) << lx.error().message;
  EXPECT_DOUBLE_EQ(*lx, sun::clearSkySource(noon, kSimulatedSite)->illuminance_lx);
  // Brighter at noon than in the early morning, and none at night.
  const auto morning = simulatedSourceIlluminance(utc("2026-06-21T05:00:00Z"), kSimulatedSite);
  ASSERT_TRUE(morning);
  EXPECT_LT(*morning, 0.8 * *lx);
  EXPECT_FALSE(simulatedSourceIlluminance(utc("2026-06-21T23:00:00Z"), kSimulatedSite));
}

#if GLARECAM_WITH_MODBUS

TEST_F(DaemonTest, EachStackRecordsTheSourceSampledDuringItsBracket) {
  writeConfig({.extra = kSimInstrument});
  auto daemon = makeDaemon();
  terminateAt(1s, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto written = stacks();
  ASSERT_EQ(written.size(), 1u);
  const nlohmann::json m = manifest(written[0]);
  ASSERT_TRUE(m.contains("source")) << m.dump();
  // The lab rig has no [site]: the simulated instrument serves its default 90 klx.
  EXPECT_EQ(m["source"]["origin"], "sensor");
  EXPECT_NEAR(m["source"]["illuminance_lx"].get<double>(), 90'000, 0.1);
  EXPECT_GE(m["source"]["samples"].get<int>(), 1);
  EXPECT_NEAR(
      m["source"]["illuminance_u_lx"].get<double>(),
      90'000 * std::hypot(0.02, rig::kDefaultDirectEfficacyULmW / rig::kDefaultDirectEfficacyLmW),
      1.0);
  EXPECT_NE(m["source"]["instrument"].get<std::string>().find("modbus:sim:127.0.0.1:"),
            std::string::npos);
  EXPECT_TRUE(m["daemon"]["flags"].empty());
  ASSERT_TRUE(daemon->state().last_source_illuminance);
  EXPECT_NEAR(daemon->state().last_source_illuminance->illuminance_lx, 90'000, 0.1);
  EXPECT_TRUE(daemon->state().illuminance_fault.empty());
}

// Every fault of the instrument: the stack is still taken, without a source, flagged, and the
// status and the journal say why. Never a number.
TEST_F(DaemonTest, AFailingInstrumentLeavesTheStacksUnreferred) {
  for (const char* fault : {"dead", "exception", "out-of-range", "negative"}) {
    SCOPED_TRACE(fault);
    std::filesystem::remove_all(out());
    writeConfig({.extra = std::string(kSimInstrument) + "sim_fault = \"" + fault + "\"\n"});
    auto daemon = makeDaemon();
    terminateAt(clock_.elapsed() + 1s, *daemon);
    ASSERT_TRUE(daemon->run());
    const auto written = stacks();
    ASSERT_EQ(written.size(), 1u);
    const nlohmann::json m = manifest(written[0]);
    EXPECT_FALSE(m.contains("source")) << m["source"].dump();
    EXPECT_EQ(m["daemon"]["flags"], nlohmann::json::array({"source_illuminance_unknown"}));
    EXPECT_FALSE(daemon->state().illuminance_fault.empty());
    EXPECT_FALSE(daemon->state().last_source_illuminance);
    EXPECT_EQ(daemon->state().illuminance_failures, 1u);
    EXPECT_TRUE(statusMentioned("illuminance: "));
    // A warning, not a fault: the rig captures on (as it did before SIGTERM).
    DaemonState running = daemon->state();
    running.stopping = false;
    EXPECT_EQ(rigActivity(running).state, "capturing");
  }
}

TEST_F(DaemonTest, ASilentInstrumentTimesOutAndTheStackIsTakenUnreferred) {
  writeConfig(
      {.extra = std::string(kSimInstrument) + "sim_fault = \"timeout\"\ntimeout_ms = 50\n"});
  auto daemon = makeDaemon();
  terminateAt(1s, *daemon);
  ASSERT_TRUE(daemon->run());
  ASSERT_EQ(stacks().size(), 1u);
  EXPECT_FALSE(manifest(stacks()[0]).contains("source"));
  EXPECT_NE(daemon->state().illuminance_fault.find("no reply within 50 ms"), std::string::npos)
      << daemon->state().illuminance_fault;
}

TEST_F(DaemonTest, TheDoctorReadsTheInstrumentOnce) {
  writeConfig({.extra = kSimInstrument});
  DoctorOptions options{.config_path = config_path(),
                        .disk = &disk_,
                        .unit_state = [](const std::string&) -> Result<std::string> {
                          return std::string("inactive (dead), disabled");
                        },
                        .clock_status =
                            [] {
                              sun::ClockStatus clock;
                              clock.synchronised = true;
                              return clock;
                            }};
  const auto checks = runDoctor(options);
  const auto check = std::find_if(checks.begin(), checks.end(),
                                  [](const DoctorCheck& c) { return c.name == "illuminance"; });
  ASSERT_NE(check, checks.end());
  EXPECT_EQ(check->level, CheckLevel::kOk) << check->detail;
  EXPECT_NE(check->detail.find("90.0 klx"), std::string::npos) << check->detail;
  writeConfig({.extra = std::string(kSimInstrument) + "sim_fault = \"exception\"\n"});
  const auto faulted = runDoctor(options);
  const auto warned = std::find_if(faulted.begin(), faulted.end(),
                                   [](const DoctorCheck& c) { return c.name == "illuminance"; });
  ASSERT_NE(warned, faulted.end());
  EXPECT_EQ(warned->level, CheckLevel::kWarn);
  EXPECT_NE(warned->detail.find("exception reply"), std::string::npos) << warned->detail;
}

#endif

}  // namespace
}  // namespace glarecam::daemon
