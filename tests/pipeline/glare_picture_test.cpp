#include "pipeline/glare_picture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/angles.h"
#include "pipeline/glare_analysis.h"
#include "render/test_canvas.h"
#include "support/sim_support.h"

namespace glarecam::pipeline {
namespace {

using render::RgbImage;

struct Pictures {
  RgbImage plain, overlaid;
  testing::RenderedScene scene;
  GlareAnalysis analysis;
};

// The same scene drawn without and with the overlay; `with_ellipses` false draws the overlay of
// an analysis that found no ellipse.
Pictures render(bool with_ellipses = true, std::vector<double> thresholds_cd_m2 = {},
                bool ladder = true) {
  testing::SceneSpec spec;
  spec.lobe = testing::lobeAtLimit(30'000, 594'000, 5.0, 5.7);
  Pictures p;
  p.scene = testing::renderScene(spec);
  const calibration::CameraModel camera(p.scene.intrinsics);
  const LuminancePeak peak = findLuminancePeak(p.scene.merged);
  if (with_ellipses) {
    p.analysis = analyseGlare(
        p.scene.merged, camera, peak,
        {.limit_cd_m2 = 30'000.0, .thresholds_cd_m2 = thresholds_cd_m2, .ladder = ladder});
  }
  FalseColourOptions options;
  options.limit_cd_m2 = 30'000.0;
  p.plain = renderFalseColour(p.scene.merged, options).value();
  options.overlay = glareOverlay(p.analysis, camera, peak);
  p.overlaid = renderFalseColour(p.scene.merged, options).value();
  return p;
}

// How much brighter (sum of channels) the overlay made the brightest pixel within `radius` of
// (x, y) than the plain picture: the lines are 1.5 px wide, anti-aliased.
int lift(const Pictures& p, double x, double y, int radius = 1) {
  int best = -1000;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const int px = static_cast<int>(std::lround(x)) + dx,
                py = static_cast<int>(std::lround(y)) + dy;
      const std::uint8_t* a = rgbPixel(p.plain, px, py);
      const std::uint8_t* b = rgbPixel(p.overlaid, px, py);
      best = std::max(best, (b[0] + b[1] + b[2]) - (a[0] + a[1] + a[2]));
    }
  }
  return best;
}

TEST(GlarePicture, DrawsTheContourTheCirclesAndNothingElsewhere) {
  const Pictures p = render();
  ASSERT_TRUE(p.analysis.limit && p.analysis.limit->ellipse);
  ASSERT_EQ(p.plain.width, p.overlaid.width);
  const GlareEllipse& limit = *p.analysis.limit->ellipse;
  // Every 20th traced contour point is covered by the contour or the fitted ellipse.
  for (std::size_t i = 0; i < limit.contour_px.size(); i += 20) {
    const auto& c = limit.contour_px[i];
    const std::uint8_t* rgb = rgbPixel(p.overlaid, static_cast<int>(std::lround(c.x)),
                                       static_cast<int>(std::lround(c.y)));
    // Magenta (contour) or white (dashed fit over it): red and blue both high.
    EXPECT_GT(rgb[0], 150) << i;
    EXPECT_GT(rgb[2], 150) << i;
  }
  // The 10° circle around the maximum, straight below it: f * tan(10°) px on a pinhole camera
  // whose lobe sits on the optical axis. The faint white line lifts the dark background there.
  const double below_px = p.scene.intrinsics.fy * std::tan(radians(10.0));
  EXPECT_GT(lift(p, p.scene.centre_px.x, p.scene.centre_px.y + below_px), 60);
  // Half-way between the 5° and 10° circles, off the axes and away from the legend: untouched.
  const double between_px = p.scene.intrinsics.fy * std::tan(radians(7.5));
  EXPECT_EQ(lift(p, p.scene.centre_px.x + between_px * 0.7071,
                 p.scene.centre_px.y - between_px * 0.7071, 0),
            0);
}

// Each --thresholds ellipse is drawn (dotted pale yellow): the overlay lifts the picture along
// its traced contour, where the picture without thresholds is left alone (away from the limit
// ellipse, the axes and the circles).
TEST(GlarePicture, DrawsTheThresholdEllipses) {
  const Pictures with = render(true, {200'000.0});
  const Pictures without = render(true);
  ASSERT_EQ(with.analysis.thresholds.size(), 1u);
  ASSERT_TRUE(with.analysis.thresholds[0].ellipse);
  const GlareEllipse& e = *with.analysis.thresholds[0].ellipse;
  int lifted = 0, checked = 0;
  for (std::size_t i = 0; i < e.contour_px.size(); i += 10) {
    const auto& c = e.contour_px[i];
    ++checked;
    // Dotted: a point may fall in a gap, so most, not all, points are lifted.
    lifted += lift(with, c.x, c.y) > 60 && lift(without, c.x, c.y) < lift(with, c.x, c.y);
  }
  ASSERT_GT(checked, 10);
  EXPECT_GT(lifted, checked / 3) << lifted << " of " << checked;
}

// The contour ladder's fixed rungs are drawn (thin pale cyan): the overlay lifts the picture along
// the lowest rung's traced contour (10 000 cd/m², outside the limit's), where the picture of the
// same analysis without the ladder is left alone.
TEST(GlarePicture, DrawsTheLaddersContours) {
  const Pictures with = render();
  const Pictures without = render(true, {}, false);
  ASSERT_FALSE(with.analysis.ladder.empty());
  const ContourRung& lowest = with.analysis.ladder.front();
  ASSERT_EQ(lowest.kind, ContourKind::kLadder);
  ASSERT_EQ(lowest.measurement.level_cd_m2, 1e4);
  ASSERT_TRUE(lowest.measurement.ellipse);
  const GlareEllipse& e = *lowest.measurement.ellipse;
  int lifted = 0, checked = 0;
  for (std::size_t i = 0; i < e.contour_px.size(); i += 10) {
    const auto& c = e.contour_px[i];
    ++checked;
    lifted += lift(with, c.x, c.y) > 40 && lift(without, c.x, c.y) < 10;
  }
  ASSERT_GT(checked, 10);
  EXPECT_GT(lifted, checked * 2 / 3) << lifted << " of " << checked;
}

TEST(GlarePicture, WithoutEllipsesOnlyTheCirclesAreDrawn) {
  const Pictures p = render(false);
  // Where the limit contour would cross the horizontal through the centre (2.85° out): nothing.
  const double contour_px = p.scene.intrinsics.fx * std::tan(radians(2.85));
  EXPECT_EQ(lift(p, p.scene.centre_px.x + contour_px, p.scene.centre_px.y, 0), 0);
  // The 5° circle is still there.
  const double circle_px = p.scene.intrinsics.fy * std::tan(radians(5.0));
  EXPECT_GT(lift(p, p.scene.centre_px.x, p.scene.centre_px.y + circle_px), 60);
}

}  // namespace
}  // namespace glarecam::pipeline
