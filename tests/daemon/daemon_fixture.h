// The fixture of glarecamd's core on the test doubles (daemon_test_support.h): a config written
// for the lab rig of the tests, and the daemon made on the manual clock, the recording notifier,
// the scripted disk and cameras, its output read back. Shared by the tests of the daemon loop
// (capture_daemon_test.cpp), of its config (daemon_config_test.cpp) and of the rig around the
// camera (hardware/).
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/json.h"
#include "daemon/capture_daemon.h"
#include "daemon/daemon_test_support.h"
#include "daemon/storage/day_products.h"
#include "support/test_support.h"

namespace glarecam::daemon {

// The lab rig of the tests: a lamp on the horizon due south, the module on a table tilted 50°
// facing it, so α = 90° − 50° = 40° (docs/rig.md); the small simulated camera; the simulated
// GPIO chip with a LED.
struct RigSpec {
  std::string camera = testing::kSmallSimCamera;
  std::string inclinometer = "sim:50";
  std::string schedule = "mode = \"interval\"\ninterval_s = 600";
  std::string faults = "camera_backoff_s = 2\ncamera_backoff_max_s = 16\ncamera_max_failures = 5";
  bool site = false;     // [site] at 48° N instead of the lab lamp (α from the sun)
  std::string output{};  // more [output] keys
  int reserve_mb = 100;
  std::string extra{};  // more sections
};

inline std::string rigToml(const RigSpec& spec) {
  std::string text = "camera = \"" + spec.camera + "\"\n";
  text += spec.site ? "[site]\nlatitude_deg = 48\nlongitude_deg = 7.85\naltitude_m = 278\n"
                    : "[source]\nelevation_deg = 0\nazimuth_deg = 180\n";
  text += "[module]\nazimuth_deg = 180\n";
  text += "[inclinometer]\nuri = \"" + spec.inclinometer + "\"\nsamples = 4\n";
  text += "[gpio]\nchip = \"sim\"\nled = 27\n";
  text += "[output]\nroot = \"out\"\nreserve_mb = " + std::to_string(spec.reserve_mb) + "\n" +
          spec.output + "\n";
  text += "[schedule]\n" + spec.schedule + "\n";
  text += "[faults]\n" + spec.faults + "\n";
  return text + spec.extra;
}

// The config of `spec`, written into `directory` as glarecam.toml and read back (a failure to
// read it fails the test, and gives the default config).
inline Config labConfig(const std::filesystem::path& directory, const RigSpec& spec = {}) {
  testing::writeText(directory / "glarecam.toml", rigToml(spec));
  const auto config = readConfig(directory / "glarecam.toml");
  EXPECT_TRUE(config) << config.error().message;
  return config.value_or(Config{});
}

class DaemonTest : public ::testing::Test {
 protected:
  void SetUp() override { spdlog::set_level(spdlog::level::warn); }

  std::filesystem::path writeConfig(const RigSpec& spec = {}) {
    testing::writeText(config_path(), rigToml(spec));
    return config_path();
  }
  std::filesystem::path config_path() const { return dir_ / "glarecam.toml"; }
  std::filesystem::path out() const { return dir_ / "out"; }

  // The daemon on the test's clock, notifier, disk and cameras, its worker inline; `adjust`
  // changes the services (a worker thread, an opener of its own).
  std::unique_ptr<CaptureDaemon> makeDaemon(
      DaemonOptions options = {}, const std::function<void(DaemonServices&)>& adjust = {}) {
    if (options.config_path == rig::kDefaultRigConfigPath) options.config_path = config_path();
    DaemonServices services{.clock = &clock_,
                            .notifier = &notifier_,
                            .disk = &disk_,
                            .open_camera = cameras_.opener(),
                            .worker_mode = StackWorker::Mode::kInline,
                            .watch_button = false};
    if (adjust) adjust(services);
    auto daemon = CaptureDaemon::create(options, std::move(services));
    EXPECT_TRUE(daemon) << daemon.error().message;
    return daemon ? std::move(*daemon) : nullptr;
  }
  // Its worker on a thread of its own.
  std::unique_ptr<CaptureDaemon> makeThreadedDaemon() {
    return makeDaemon(
        {}, [](DaemonServices& services) { services.worker_mode = StackWorker::Mode::kThread; });
  }
  // With its worker on a thread, held at the start of its first job by `gate`.
  template <typename Gate>
  std::unique_ptr<CaptureDaemon> makeGatedDaemon(Gate& gate, DaemonOptions options = {}) {
    return makeDaemon(std::move(options), [&gate](DaemonServices& services) {
      services.worker_mode = StackWorker::Mode::kThread;
      services.worker_job_hook = [&gate] { gate.hold(); };
    });
  }

  // SIGTERM (through the event queue, as the signal forwarder posts it) at `offset`.
  void terminateAt(std::chrono::nanoseconds offset, CaptureDaemon& daemon) {
    signalAt(offset, daemon, SIGTERM);
  }
  void signalAt(std::chrono::nanoseconds offset, CaptureDaemon& daemon, int signal) {
    clock_.at(offset, [&daemon, signal] { daemon.events().post(SignalEvent{signal}); });
  }

  // At `offset` the stacks directory turns into a file: a refusal statvfs cannot see.
  void refuseStacksAt(std::chrono::nanoseconds offset) {
    clock_.at(offset, [this] {
      std::filesystem::remove_all(out() / kStacksDirectory);
      testing::writeText(out() / kStacksDirectory, "not a directory");
    });
  }

  // From `from` to `to`, results/ is a file (the directory set aside): processing cannot write a
  // result (kIo) and the output tree is not writable; stacks written before stay.
  void refuseResultsBetween(std::chrono::nanoseconds from, std::chrono::nanoseconds to) {
    const std::filesystem::path results = out() / kResultsDirectory;
    const std::filesystem::path aside = out() / "results-aside";
    clock_.at(from, [results, aside] {
      std::filesystem::rename(results, aside);
      testing::writeText(results, "not a directory");
    });
    clock_.at(to, [results, aside] {
      std::filesystem::remove(results);
      std::filesystem::rename(aside, results);
    });
  }

  std::vector<std::filesystem::path> stacks() const { return entries(out() / kStacksDirectory); }
  std::vector<std::filesystem::path> results() const { return entries(out() / kResultsDirectory); }
  static std::vector<std::filesystem::path> entries(const std::filesystem::path& directory) {
    std::vector<std::filesystem::path> found;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error))
      found.push_back(entry.path());
    std::sort(found.begin(), found.end());
    return found;
  }
  static nlohmann::json manifest(const std::filesystem::path& stack) {
    return *readJsonFile((stack / "stack.json").string());
  }
  bool statusMentioned(const std::string& text) const {
    for (const auto& status : notifier_.matching("STATUS="))
      if (status.message.find(text) != std::string::npos) return true;
    return false;
  }

  testing::TempDir dir_;
  testing::ManualClock clock_{testing::utc("2026-06-21T08:00:00Z")};
  testing::RecordingNotifier notifier_{clock_, std::chrono::seconds(10)};
  testing::ScriptedDisk disk_;
  testing::ScriptedCameras cameras_;
};

}  // namespace glarecam::daemon
