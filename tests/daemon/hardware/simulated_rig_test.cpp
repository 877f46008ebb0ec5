// glarecamd --simulate's rig (daemon/hardware/simulated_rig.h) in the daemon, on a time lapse of
// the manual clock, with brackets that take the manual clock's time: each stack records the α its
// scene was drawn at, however long its bracket.
#include "daemon/hardware/simulated_rig.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "core/json.h"
#include "daemon/daemon_fixture.h"
#include "daemon/hardware/rig_doctor.h"
#include "daemon/status/status_page.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;

class SimulatedRigTest : public DaemonTest {
 protected:
  // The daemon on the simulated rig's config (with the small camera) and on `clock`, stopping
  // after `stacks`.
  std::unique_ptr<CaptureDaemon> makeSimulatedDaemon(DaemonClock& clock, std::uint64_t stacks,
                                                     StatusBoard* board = nullptr) {
    const auto config = writeSimulatedRigConfig(
        {.output = out(), .camera = testing::kSmallSimCamera, .interval = std::nullopt});
    EXPECT_TRUE(config) << config.error().message;
    auto daemon = CaptureDaemon::create({.config_path = config.value_or(""), .max_stacks = stacks},
                                        {.clock = &clock,
                                         .notifier = &notifier_,
                                         .disk = &disk_,
                                         .open_camera = cameras_.opener(),
                                         .worker_mode = StackWorker::Mode::kInline,
                                         .watch_button = false,
                                         .status_board = board});
    EXPECT_TRUE(daemon) << daemon.error().message;
    return daemon ? std::move(*daemon) : nullptr;
  }
};

TEST_F(SimulatedRigTest, EveryStackOfAMorningRecordsTheAlphaItsSceneWasDrawnAt) {
  TimeLapseClock time_lapse(defaultSimulationStart(true), kDefaultTimeLapse, clock_);
  // Each of the camera's captures (the metering's and the bracket's) takes a second of real time:
  // two minutes of the time lapse's sun, which must not move the α recorded for the bracket.
  cameras_.takeCaptureTime(clock_, 1s);
  const auto daemon = makeSimulatedDaemon(time_lapse, 16);
  ASSERT_TRUE(daemon);
  const Status ran = daemon->run();
  ASSERT_TRUE(ran) << ran.error().message;
  const auto taken = stacks();
  ASSERT_EQ(taken.size(), 16u);
  for (const std::filesystem::path& stack : taken) {
    const nlohmann::json recorded = manifest(stack);
    const auto truth = readJsonFile((stack / "truth.json").string());
    ASSERT_TRUE(truth) << truth.error().message;
    ASSERT_TRUE(recorded.contains("alpha_deg")) << stack.filename();
    EXPECT_NEAR(recorded["alpha_deg"].get<double>(), (*truth)["alpha_deg"].get<double>(), 0.05)
        << stack.filename() << ": the manifest's α against the scene's";
  }
}

// The status page and /metrics said the simulated rig's clock was synchronised, glarecam doctor on
// the same config that it was not: one answer now, on the time lapse and on the machine's clock
// alike (glarecamd --config on the simulated rig's file), while the machine's is unsynchronised.
TEST_F(SimulatedRigTest, TheStatusAndTheDoctorAgreeTheSimulatedRigsClockIsSynchronised) {
  const sun::ClockStatus unsynchronised{.synchronised = false, .detail = "kernel: STA_UNSYNC"};
  clock_.setClockStatus(unsynchronised);
  TimeLapseClock time_lapse(defaultSimulationStart(true), kDefaultTimeLapse, clock_);
  for (DaemonClock* clock :
       {static_cast<DaemonClock*>(&time_lapse), static_cast<DaemonClock*>(&clock_)}) {
    StatusBoard board;
    const auto daemon = makeSimulatedDaemon(*clock, 1, &board);
    ASSERT_TRUE(daemon);
    ASSERT_TRUE(daemon->run());
    ASSERT_TRUE(board.latest());
    EXPECT_TRUE(board.latest()->clock_synchronised);
    EXPECT_NE(statusMetrics(*board.latest()).find("glarecam_clock_synchronised 1"),
              std::string::npos);
    EXPECT_EQ(board.latest()->state.clock_warning, "");
    EXPECT_EQ(manifest(stacks().back())["daemon"]["flags"], nlohmann::json::array());
  }
  DoctorOptions doctor{
      .config_path = out() / kSimulatedRigFileName,
      .disk = &disk_,
      .unit_state = [](const std::string&) -> Result<std::string> { return "inactive"; },
      .clock_status = [&unsynchronised] { return unsynchronised; }};
  const std::vector<DoctorCheck> checks = runDoctor(doctor);
  const auto clock = std::find_if(checks.begin(), checks.end(),
                                  [](const DoctorCheck& c) { return c.name == "clock"; });
  ASSERT_NE(clock, checks.end());
  EXPECT_EQ(clock->level, CheckLevel::kOk) << clock->detail;
}

}  // namespace
}  // namespace glarecam::daemon
