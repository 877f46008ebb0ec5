// glarecamd --simulate's rig (daemon/hardware/simulated_rig.h) in the daemon, on a time lapse of
// the manual clock, with brackets that take the manual clock's time: each stack records the α its
// scene was drawn at, however long its bracket.
#include "daemon/hardware/simulated_rig.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "core/json.h"
#include "daemon/alpha_schedule.h"
#include "daemon/daemon_fixture.h"
#include "daemon/hardware/rig_doctor.h"
#include "daemon/status/status_page.h"
#include "rig/illuminance/illuminance_registry.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;
using testing::utc;

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
    // The simulated pyrheliometer, read over Modbus TCP on loopback during the bracket, gave
    // the clear-sky sun of the bracket's start (captured_at: to the second, and E changes far
    // less than 0.1 % in a second of the time lapse).
    if (!rig::modbusAvailable()) continue;  // built without: the rig has no instrument
    ASSERT_TRUE(recorded.contains("source")) << stack.filename();
    EXPECT_EQ(recorded["source"]["origin"], "sensor");
    const auto captured = parseIsoTime(recorded["captured_at"].get<std::string>());
    ASSERT_TRUE(captured);
    const auto clear_sky =
        simulatedSourceIlluminance(*captured, {.latitude_deg = kSimulatedLatitudeDeg,
                                               .longitude_deg = kSimulatedLongitudeDeg,
                                               .altitude_m = 278,
                                               .pressure_hpa = sun::standardPressureHpa(278)});
    ASSERT_TRUE(clear_sky) << clear_sky.error().message;
    EXPECT_NEAR(recorded["source"]["illuminance_lx"].get<double>(), *clear_sky, 1e-3 * *clear_sky)
        << stack.filename();
  }
}

// Bytes under `directory`, recursively.
std::uint64_t bytesUnder(const std::filesystem::path& directory) {
  std::uint64_t bytes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(directory))
    if (entry.is_regular_file()) bytes += entry.file_size();
  return bytes;
}

// The docs' first example, `glarecamd --simulate --output DIR` left running, overran its own
// 0.2 GiB budget in the first afternoon (today's stacks never go). Its worst day: a day's stacks
// (kept keep_stacks_days) and results (keep_results_days), each as large as the largest, the
// stack at α 10° taken here with the default camera (α 5° … 80°: 6.0 … 6.9 MB, results 4.6 MB),
// and a day's sheets, must fit the budget with a tenth to spare.
TEST_F(SimulatedRigTest, TheDefaultRunsWorstDayFitsItsBudget) {
  const auto path = writeSimulatedRigConfig({.output = out(), .interval = std::nullopt});
  ASSERT_TRUE(path) << path.error().message;
  const auto config = readConfig(*path);
  ASSERT_TRUE(config) << config.error().message;
  const RetentionPolicy& retention = config->daemon.output.retention;
  ASSERT_TRUE(retention.max_use_bytes) << "no budget";
  ASSERT_TRUE(retention.keep_stacks_days && retention.keep_results_days)
      << "without ages, the results of every day stay";
  // The stacks of a day: each α target crossed while the sun is up, from the simulated start on.
  const UtcTime start = defaultSimulationStart(true);
  const auto crossings =
      alphaCrossings(*config->rig.site, {.tilt_deg = kSimulatedTiltDeg, .azimuth_deg = 180}, start,
                     std::chrono::hours(24), config->daemon.schedule.alpha_targets_deg);
  ASSERT_TRUE(crossings) << crossings.error().message;
  const std::uint64_t stacks_a_day = crossings->size();
  EXPECT_EQ(stacks_a_day, 32u);
  // One stack and its result at α 10°, on the simulated rig as it is written (no small camera).
  TimeLapseClock time_lapse(utc("2026-06-21T10:44:00Z"), kDefaultTimeLapse, clock_);
  auto daemon = CaptureDaemon::create({.config_path = *path, .max_stacks = 1},
                                      {.clock = &time_lapse,
                                       .notifier = &notifier_,
                                       .disk = &disk_,
                                       .worker_mode = StackWorker::Mode::kInline,
                                       .watch_button = false});
  ASSERT_TRUE(daemon) << daemon.error().message;
  ASSERT_TRUE((*daemon)->run());
  ASSERT_EQ(stacks().size(), 1u);
  const std::uint64_t stack_bytes = bytesUnder(out() / kStacksDirectory);
  const std::uint64_t result_bytes = bytesUnder(out() / kResultsDirectory);
  constexpr std::uint64_t kDaySheetsBytes = 2ull << 20;  // a day's sweep, fits and sheets: 0.9 MB
  const double worst_day_bytes =
      static_cast<double>(stacks_a_day) *
          static_cast<double>(stack_bytes * *retention.keep_stacks_days +
                              result_bytes * *retention.keep_results_days) +
      static_cast<double>(kDaySheetsBytes * *retention.keep_results_days);
  EXPECT_LT(1.1 * worst_day_bytes, static_cast<double>(*retention.max_use_bytes))
      << stacks_a_day << " stacks a day of " << stack_bytes << " bytes, results of " << result_bytes
      << " bytes";
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
