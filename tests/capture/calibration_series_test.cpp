// Capturing a calibration part's stacks from the simulated camera in front of a target: each view
// one stack of the given exposures, written to the series' directory; bad options refused
// before the camera is opened.
#include "capture/calibration_series.h"

#include <gtest/gtest.h>

#include <set>

#include "core/stack_io.h"
#include "support/test_support.h"

namespace glarecam::capture {
namespace {

namespace fs = std::filesystem;

CalibrationSeriesOptions flatSeries(const fs::path& directory) {
  CalibrationSeriesOptions options;
  options.camera_uri = "sim:target=flat,size=80x64";
  options.exposures_us = {2000, 2000, 500};
  options.directory = directory;
  return options;
}

TEST(CalibrationSeries, EachViewIsOneStackOfTheExposures) {
  testing::TempDir dir;
  CalibrationSeriesOptions options = flatSeries(dir / "flat-stacks");
  options.views = 3;
  options.view_interval_s = 0;
  const auto paths = captureCalibrationSeries(options);
  ASSERT_TRUE(paths) << paths.error().message;
  ASSERT_EQ(paths->size(), 3u);
  EXPECT_EQ(std::set<fs::path>(paths->begin(), paths->end()).size(), 3u) << "one stack a view";
  for (const fs::path& path : *paths) {
    EXPECT_EQ(path.parent_path(), dir / "flat-stacks");
    StackReadOptions read;
    read.require_calibration = false;
    const auto stack = readStack(path, read);
    ASSERT_TRUE(stack) << stack.error().message;
    ASSERT_EQ(stack->manifest.frames.size(), 3u);
    EXPECT_EQ(stack->manifest.frames[0].exposure_us, 2000);
    EXPECT_EQ(stack->manifest.frames[1].exposure_us, 2000);
    EXPECT_EQ(stack->manifest.frames[2].exposure_us, 500);
    EXPECT_TRUE(stack->frames.front().sameSize(80, 64));
  }
}

TEST(CalibrationSeries, BadOptionsAreRefusedBeforeCapturing) {
  testing::TempDir dir;
  const auto refused = [&](CalibrationSeriesOptions options, const std::string& message) {
    const auto paths = captureCalibrationSeries(options);
    ASSERT_FALSE(paths);
    EXPECT_EQ(paths.error().code, ErrorCode::kBadInput);
    EXPECT_NE(paths.error().message.find(message), std::string::npos) << paths.error().message;
    EXPECT_FALSE(fs::exists(options.directory));
  };
  CalibrationSeriesOptions options = flatSeries(dir / "stacks");
  options.views = 0;
  refused(options, "--views must be at least 1");
  options = flatSeries(dir / "stacks");
  options.view_interval_s = 3601;
  refused(options, "--view-interval must be between 0 and 3600 s");
  options = flatSeries(dir / "stacks");
  options.exposures_us.clear();
  refused(options, "expected 1 to 256 exposures, got 0");
  options = flatSeries(dir / "stacks");
  options.camera_uri = "sim:target=sphere";
  refused(options, "unknown calibration target \"sphere\"");
}

}  // namespace
}  // namespace glarecam::capture
