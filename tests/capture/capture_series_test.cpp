// A series of bracketed stacks from the sim: camera: `count` stacks `interval` apart, each written
// as soon as it is complete, its options checked before anything is captured, a rig preparing and
// finishing each stack, and a stop request or a failed capture ending the series.
#include "capture/capture_series.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "capture/test_cameras.h"
#include "core/stack_io.h"
#include "support/test_support.h"

namespace glarecam::capture {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::CountingCamera;
using testing::kSimLimits;
using testing::openSim;
using testing::TempDir;

CaptureSettings oneExposure() {
  CaptureSettings settings;
  settings.exposures_us = std::vector<double>{1000};
  settings.alpha_deg = 40;
  return settings;
}

// A series into `out`, each written stack's path appended to `written`.
SeriesOptions seriesInto(const fs::path& out, std::uint64_t count, std::vector<fs::path>& written) {
  SeriesOptions options;
  options.out = out;
  options.count = count;
  options.on_written = [&written](const fs::path& path) { written.push_back(path); };
  return options;
}

// A rig that sets α per stack and notes the brackets' times; it stops at `stop_at`.
class RecordingRig final : public SeriesRig {
 public:
  explicit RecordingRig(std::uint64_t stop_at = 100) : stop_at_(stop_at) {}
  Result<bool> prepareStack(CaptureSettings& settings, std::uint64_t index) override {
    prepared.push_back(index);
    if (index == stop_at_) return false;
    settings.alpha_deg = 30.0 + 10.0 * static_cast<double>(index);
    return true;
  }
  void finishStack(CapturedStack& stack, UtcTime bracket_start, UtcTime bracket_end) override {
    brackets.emplace_back(bracket_start, bracket_end);
    stack.manifest.source["rig"] = "recorded";
  }
  std::vector<std::uint64_t> prepared;
  std::vector<std::pair<UtcTime, UtcTime>> brackets;

 private:
  std::uint64_t stop_at_;
};

TEST(CaptureSeries, EachStackIsWrittenAsSoonAsItIsComplete) {
  TempDir dir;
  auto camera = openSim("size=64x48");
  ASSERT_TRUE(camera);
  std::vector<fs::path> written;
  ASSERT_TRUE(captureSeries(*camera, oneExposure(), seriesInto(dir / "out", 3, written)));
  ASSERT_EQ(written.size(), 3u);
  for (const fs::path& stack : written) {
    EXPECT_EQ(stack.parent_path(), dir / "out");
    const auto read = readStack(stack);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->manifest.alpha_deg, 40.0);
  }
  EXPECT_NE(written[0], written[1]);  // never one over another
  EXPECT_NE(written[1], written[2]);
}

TEST(CaptureSeries, BracketsStartAnIntervalApart) {
  TempDir dir;
  auto camera = openSim("size=64x48");
  ASSERT_TRUE(camera);
  std::vector<fs::path> written;
  SeriesOptions options = seriesInto(dir / "out", 3, written);
  options.interval = 0.2s;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(captureSeries(*camera, oneExposure(), options));
  // The third bracket starts two intervals after the first: a lower bound only (a loaded machine
  // may be slower, never faster).
  EXPECT_GE(std::chrono::steady_clock::now() - start, 0.4s);
  EXPECT_EQ(written.size(), 3u);
}

TEST(CaptureSeries, OptionsAreCheckedBeforeAnythingIsCaptured) {
  TempDir dir;
  CountingCamera camera(kSimLimits);
  std::vector<fs::path> written;
  const auto refused = [&](const SeriesOptions& options) {
    const Status status = captureSeries(camera, oneExposure(), options);
    EXPECT_FALSE(status);
    return status ? std::string() : status.error().message;
  };
  SeriesOptions options = seriesInto(dir / "out", 0, written);
  EXPECT_EQ(refused(options), "capture: --count must be at least 1");
  options.count = 1;
  options.interval = -1s;
  EXPECT_EQ(refused(options), "capture: --interval must be between 0 and 604800 seconds (a week)");
  options.interval = kMaxSeriesInterval + 1s;
  EXPECT_EQ(refused(options), "capture: --interval must be between 0 and 604800 seconds (a week)");
  options.interval = kMaxSeriesInterval;
  options.out.clear();
  EXPECT_EQ(refused(options), "capture: --out must not be empty");
  EXPECT_EQ(camera.calls(), 0);
  EXPECT_TRUE(written.empty());
}

TEST(CaptureSeries, ARigPreparesAndFinishesEveryStack) {
  TempDir dir;
  auto camera = openSim("size=64x48");
  ASSERT_TRUE(camera);
  RecordingRig rig;
  std::vector<fs::path> written;
  ASSERT_TRUE(captureSeries(*camera, oneExposure(), seriesInto(dir / "out", 2, written), &rig));
  EXPECT_EQ(rig.prepared, (std::vector<std::uint64_t>{0, 1}));
  ASSERT_EQ(rig.brackets.size(), 2u);
  for (const auto& [bracket_start, bracket_end] : rig.brackets)
    EXPECT_LE(bracket_start, bracket_end);
  ASSERT_EQ(written.size(), 2u);
  for (std::size_t i = 0; i < written.size(); ++i) {
    const auto read = readStack(written[i]);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->manifest.alpha_deg, 30.0 + 10.0 * static_cast<double>(i));
    EXPECT_EQ(read->manifest.source["rig"], "recorded");
  }
}

TEST(CaptureSeries, ARigStoppedWhileWaitingEndsTheSeries) {
  TempDir dir;
  auto camera = openSim("size=64x48");
  ASSERT_TRUE(camera);
  RecordingRig rig(1);  // stopped while waiting for the second stack's button
  std::vector<fs::path> written;
  const Status status =
      captureSeries(*camera, oneExposure(), seriesInto(dir / "out", 3, written), &rig);
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kInternal);
  EXPECT_EQ(status.error().message, "capture: interrupted after 1 of 3 stacks");
  EXPECT_EQ(written.size(), 1u);
}

TEST(CaptureSeries, AFailedCaptureEndsTheSeriesWithItsError) {
  TempDir dir;
  CountingCamera camera(kSimLimits, CountingCamera::Answer::kError);
  std::vector<fs::path> written;
  const Status status = captureSeries(camera, oneExposure(), seriesInto(dir / "out", 3, written));
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kHardware);
  EXPECT_EQ(status.error().message, "test:counting: control-lost");
  EXPECT_EQ(camera.calls(), 1);
  EXPECT_TRUE(written.empty());
}

// A rig that sends this process SIGINT while preparing stack `at`, as Ctrl-C would.
class InterruptingRig final : public SeriesRig {
 public:
  explicit InterruptingRig(std::uint64_t at) : at_(at) {}
  Result<bool> prepareStack(CaptureSettings&, std::uint64_t index) override {
    if (index == at_) ::kill(::getpid(), SIGINT);
    return true;
  }
  void finishStack(CapturedStack&, UtcTime, UtcTime) override {}

 private:
  std::uint64_t at_;
};

// Ctrl-C changes the process for good (core/interruption.h): in a child process of its own.
TEST(CaptureSeries, AStopRequestEndsTheSeriesAfterTheStackBeingTaken) {
  TempDir dir;
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    auto camera = openSim("size=64x48");
    if (!camera) ::_exit(1);
    InterruptingRig rig(1);
    std::vector<fs::path> written;
    const Status status =
        captureSeries(*camera, oneExposure(), seriesInto(dir / "out", 4, written), &rig);
    if (status || status.error().message != "capture: interrupted after 2 of 4 stacks") ::_exit(2);
    ::_exit(written.size() == 2 ? 0 : 3);  // the stack being taken was finished and written
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
}

}  // namespace
}  // namespace glarecam::capture
