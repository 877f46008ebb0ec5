// The statistics every calibration procedure builds on: regions, means and variances of frames
// and of their differences, robust spreads, and the grouping of frames by exposure.
#include "calibration/frame_statistics.h"

#include <gtest/gtest.h>

namespace glarecam {
namespace {

TEST(Roi, ParsesXYWidthHeightAndRefusesEverythingElse) {
  const auto roi = calibration::parseRoi("10,20,30,40", "--roi");
  ASSERT_TRUE(roi) << roi.error().message;
  EXPECT_EQ(roi->x, 10);
  EXPECT_EQ(roi->height, 40);
  for (const char* bad : {"", "1,2,3", "1,2,3,4,5", "a,2,3,4", "1,2,0,4", "-1,2,3,4", "1,,3,4",
                          "1,2,3,4x", "99999999999,1,1,1"}) {
    const auto parsed = calibration::parseRoi(bad, "--roi");
    ASSERT_FALSE(parsed) << bad;
    EXPECT_NE(parsed.error().message.find("--roi"), std::string::npos);
  }
  EXPECT_FALSE(calibration::checkRoi({.x = 90, .y = 0, .width = 20, .height = 10}, 100, 100, "r"));
  EXPECT_TRUE(calibration::checkRoi({.x = 80, .y = 90, .width = 20, .height = 10}, 100, 100, "r"));
  // x + w beyond int: refused, not wrapped into a negative sum that passes.
  EXPECT_FALSE(
      calibration::checkRoi({.x = 2147483000, .y = 0, .width = 1000, .height = 10}, 100, 100, "r"));
  const calibration::Roi central = calibration::centralRoi(100, 60);
  EXPECT_EQ(central.x, 25);
  EXPECT_EQ(central.width, 50);
  EXPECT_EQ(central.height, 30);
}

TEST(FrameStatistics, MeansVariancesAndDifferencesOverARegion) {
  RawFrame a(4, 2), b(4, 2);
  const std::uint16_t va[] = {4000, 4002, 4004, 4006, 4000, 4002, 4004, 4006};
  const std::uint16_t vb[] = {4000, 4000, 4000, 4000, 4000, 4000, 4000, 4000};
  std::copy(std::begin(va), std::end(va), a.data());
  std::copy(std::begin(vb), std::end(vb), b.data());
  const calibration::Roi all{.x = 0, .y = 0, .width = 4, .height = 2};
  const calibration::RegionStats stats = calibration::regionStats(a, all);
  EXPECT_DOUBLE_EQ(stats.mean_dn, 4003);
  EXPECT_NEAR(stats.variance_dn2, 40.0 / 7.0, 1e-9);  // deviations ±1, ±3: 20 / 7 per row pair
  EXPECT_EQ(stats.max_dn, 4006);
  const calibration::RegionStats diff = calibration::differenceStats(a, b, all);
  EXPECT_DOUBLE_EQ(diff.mean_dn, 3);
  EXPECT_NEAR(diff.variance_dn2, 40.0 / 7.0, 1e-9);
  const RawFrame* frames[] = {&a, &b};
  const FloatImage mean = calibration::meanFrame(frames, 4000);
  EXPECT_FLOAT_EQ(mean.at(3, 1), 3);
}

TEST(FrameStatistics, RobustSpreadIgnoresOutliers) {
  FloatImage image(100, 1);
  for (int x = 0; x < 100; ++x) image.at(x, 0) = static_cast<float>(x % 2 ? 11 : 9);
  image.at(0, 0) = 1e6f;  // a hot pixel
  const calibration::RobustSpread spread = calibration::robustSpread(image);
  // The median of 9s and 11s is one of them, their MAD 2 (or 0): the hot pixel moves neither,
  // where it would make the standard deviation 1e5.
  EXPECT_NEAR(spread.median, 10, 1.0);
  EXPECT_LE(spread.sigma, 1.4826 * 2 + 1e-9);
}

TEST(FrameStatistics, FramesGroupByExposureAndGain) {
  const auto spec = [](double exposure_us, double gain_db) {
    FrameSpec frame;
    frame.exposure_us = exposure_us;
    frame.gain_db = gain_db;
    return frame;
  };
  const std::vector<FrameSpec> specs{spec(200, 0), spec(100, 0), spec(200.0000001, 0),
                                     spec(100, 6)};
  const auto groups = calibration::groupByExposure(specs);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].exposure_us, 100);
  EXPECT_EQ(groups[0].gain_db, 0);  // by exposure, then gain
  EXPECT_EQ(groups[1].gain_db, 6);
  EXPECT_EQ(groups.back().frames, (std::vector<std::size_t>{0, 2}));
  const auto mixed = calibration::checkOneGain(groups, "linearity");
  ASSERT_FALSE(mixed);
  EXPECT_NE(mixed.error().message.find("frames at 0 dB and 6 dB"), std::string::npos);
}

}  // namespace
}  // namespace glarecam
