// The ocular hazard plot: the page as PNG and SVG written atomically; each zone's fill where its
// class is (the data area located in the PNG by the extent of the fills, then points of known
// class looked up at their place on the log axes); no yellow where the boundaries have crossed;
// a point in its series' ink at its place and one beyond the axes drawn hollow at the edge; the
// same plot drawn into a box of a canvas; bad content refused with nothing written or drawn; an
// unwritable path an error.
#include "hazard/ocular_hazard_plot.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <png.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "hazard/ocular_hazard.h"
#include "render/canvas.h"
#include "render/colour.h"
#include "render/rgb_surface.h"
#include "support/test_support.h"

namespace glarecam::hazard {
// Named after the file: in a unity build the test files share translation units.
namespace ocular_hazard_plot_test {

namespace fs = std::filesystem;

using Pixel = glarecam::testing::RgbPixel;

// An A4 landscape page at 144 dpi.
constexpr int kPngWidth = 1684, kPngHeight = 1190;

const Pixel kInkPixel = render::rgbBytes(render::kInk);  // series 0's marker
// Cairo's bytes for a colour may differ by one from rgbBytes' rounding (0.1 · 255: 25, not 26).
constexpr int kCairoRounding = 1;
const Pixel kWhitePixel = {255, 255, 255};

using Png = glarecam::testing::RgbPicture;

Png fromSurface(const render::RgbSurface& surface) {
  const render::RgbImage image = surface.copyRgb();
  return {image.width, image.height, image.rgb};
}

bool isZone(const Pixel& p) {
  return p == kOcularGreenFill || p == kOcularYellowFill || p == kOcularRedFill;
}

// The data area in pixels: from x0, y0 to x1, y1 (exclusive). On a page, found as the extent of
// the zones' fills (exact to the pixel or so the frame's line covers at each edge).
struct Area {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  // The pixel of (ω mrad, E_r W/cm²) on the plot's log axes.
  std::pair<int, int> at(double angle_mrad, double irradiance_w_cm2) const {
    const double fx = (std::log10(angle_mrad) - std::log10(kOcularPlotMinAngleMrad)) /
                      (std::log10(kOcularPlotMaxAngleMrad) - std::log10(kOcularPlotMinAngleMrad));
    const double fy =
        (std::log10(irradiance_w_cm2) - std::log10(kOcularPlotMinIrradianceWCm2)) /
        (std::log10(kOcularPlotMaxIrradianceWCm2) - std::log10(kOcularPlotMinIrradianceWCm2));
    return {static_cast<int>(x0 + fx * (x1 - x0)), static_cast<int>(y1 - fy * (y1 - y0))};
  }
};

Area zoneExtent(const Png& png) {
  Area a{static_cast<double>(png.width), static_cast<double>(png.height), -1, -1};
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      if (isZone(png.at(x, y))) {
        a.x0 = std::min(a.x0, static_cast<double>(x));
        a.y0 = std::min(a.y0, static_cast<double>(y));
        a.x1 = std::max(a.x1, static_cast<double>(x + 1));
        a.y1 = std::max(a.y1, static_cast<double>(y + 1));
      }
  return a;
}

Pixel pixelAt(const Png& png, std::pair<int, int> at) { return png.at(at.first, at.second); }

// Whether some pixel within `radius` of `at` is within `tolerance` of `colour` in each channel.
bool colourNear(const Png& png, std::pair<int, int> at, const Pixel& colour, int radius,
                int tolerance = 0) {
  for (int y = at.second - radius; y <= at.second + radius; ++y)
    for (int x = at.first - radius; x <= at.first + radius; ++x) {
      if (x < 0 || y < 0 || x >= png.width || y >= png.height) continue;
      const Pixel p = png.at(x, y);
      bool close = true;
      for (int c = 0; c < 3; ++c) close = close && std::abs(p[c] - colour[c]) <= tolerance;
      if (close) return true;
    }
  return false;
}

struct Written {
  Png png;
  std::string svg;
};

Written write(const OcularPlotContent& content) {
  glarecam::testing::TempDir dir;
  const auto status = writeOcularHazardPlot(content, dir / "ocular.png", dir / "ocular.svg");
  EXPECT_TRUE(status) << status.error().message;
  if (!status) return {};
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_NE(entry.path().filename().string().rfind(".tmp-", 0), 0u) << entry.path();
  return {glarecam::testing::readPngRgb(dir / "ocular.png"),
          glarecam::testing::readText(dir / "ocular.svg")};
}

OcularPlotContent emptyPlot() {
  return {.title = "Ocular hazard at window-3, 2027", .subtitle = "test scene; SGHAT's eye"};
}

TEST(OcularHazardPlot, WritesAPngPageAndAnSvgDocument) {
  const Written written = write(emptyPlot());
  EXPECT_EQ(written.png.width, kPngWidth);
  EXPECT_EQ(written.png.height, kPngHeight);
  EXPECT_NE(written.svg.find("<svg"), std::string::npos);
  EXPECT_NE(written.svg.find("</svg>"), std::string::npos);
}

// Points of known class (ocular_hazard_test.cpp works the boundaries out by hand), chosen off the
// decades (no grid line), away from the lines (≥ 0.2 decade: 20 px) and from the legend's corner
// (the top right: the only corner no boundary crosses) and the "no glaring event" note (the
// middle). At 3 mrad the burn boundary is 39.3 W/cm² and the after-image one 13.5; at 30 mrad
// 3.93 and 0.0833; at 0.5 mrad, below the boundaries' crossing (1.24 mrad), burn 236 and
// after-image 708: there, between them, is red.
TEST(OcularHazardPlot, EachZoneIsShadedWhereItsClassIs) {
  const Png png = write(emptyPlot()).png;
  const Area area = zoneExtent(png);
  // The plot takes most of the page: 3 decades across, 9 up.
  ASSERT_GT(area.x1 - area.x0, kPngWidth * 3 / 4);
  ASSERT_GT(area.y1 - area.y0, kPngHeight * 2 / 3);
  struct Probe {
    double angle_mrad, irradiance_w_cm2;
    Pixel fill;
  };
  const std::vector<Probe> probes = {
      {3, 3e-4, kOcularGreenFill},  {3, 23, kOcularYellowFill},    {3, 300, kOcularRedFill},
      {30, 3e-4, kOcularGreenFill}, {30, 0.5, kOcularYellowFill},  {0.5, 60, kOcularGreenFill},
      {0.5, 400, kOcularRedFill},   {0.2, 3e-5, kOcularGreenFill},
  };
  for (const Probe& p : probes) {
    SCOPED_TRACE(::testing::Message()
                 << p.angle_mrad << " mrad, " << p.irradiance_w_cm2 << " W/cm2");
    // The class the fill stands for, from the library's own classification.
    const OcularClass c = classify(p.irradiance_w_cm2, p.angle_mrad).value();
    EXPECT_EQ(p.fill, c == OcularClass::kRetinalBurn  ? kOcularRedFill
                      : c == OcularClass::kAfterImage ? kOcularYellowFill
                                                      : kOcularGreenFill);
    EXPECT_EQ(pixelAt(png, area.at(p.angle_mrad, p.irradiance_w_cm2)), p.fill);
  }
  // Below the crossing there is no yellow at all: a column at 0.5 mrad from bottom to top.
  const int x = area.at(0.5, 1).first;
  for (int y = static_cast<int>(area.y0) + 2; y < static_cast<int>(area.y1) - 2; ++y)
    EXPECT_NE(png.at(x, y), kOcularYellowFill) << "y " << y;
}

TEST(OcularHazardPlot, EachEventIsAPointAndOneBeyondTheAxesIsDrawnHollowAtTheEdge) {
  OcularPlotContent c = emptyPlot();
  c.series = {{"array-1", {{3, 3e-4}, {1000, 1e-9}}}, {"array-2", {{30, 0.5}}}};
  const Png png = write(c).png;
  const Area area = zoneExtent(png);
  ASSERT_GT(area.x1 - area.x0, kPngWidth * 3 / 4);
  // array-1's point: a filled near-black circle of 3.6 pt (7 px) at its place.
  EXPECT_TRUE(colourNear(png, area.at(3, 3e-4), kInkPixel, 1, kCairoRounding));
  // array-2's: Okabe–Ito blue.
  EXPECT_TRUE(colourNear(png, area.at(30, 0.5), {0x00, 0x72, 0xB2}, 1, kCairoRounding));
  // The point beyond both axes (1000 mrad, 1e-9 W/cm²) at the bottom right corner: white inside,
  // a ring of array-1's ink (antialiased: within a few levels of it).
  const std::pair<int, int> corner{static_cast<int>(area.x1) - 1, static_cast<int>(area.y1) - 1};
  EXPECT_TRUE(colourNear(png, corner, kWhitePixel, 1));
  EXPECT_TRUE(colourNear(png, corner, kInkPixel, 6, 24));
  // Without the point beyond, the corner is the zone's and the frame's: no white there.
  c.series[0].points.pop_back();
  const Png without = write(c).png;
  EXPECT_FALSE(colourNear(without, corner, kWhitePixel, 1));
}

// The same plot drawn into a box of a canvas (a report page embeds it): the zones fill its data
// area as on the page, the point is at its place, and nothing is drawn outside the box.
TEST(OcularHazardPlot, DrawsIntoABoxOfACanvas) {
  constexpr int kWidth = 900, kHeight = 700;
  auto surface = render::RgbSurface::create(kWidth, kHeight);
  ASSERT_TRUE(surface) << surface.error().message;
  auto canvas = render::Canvas::onSurface(*surface);
  ASSERT_TRUE(canvas) << canvas.error().message;
  render::paint(*canvas, render::kWhite);
  const render::Box box{100, 50, 800, 650};
  OcularPlotContent c = emptyPlot();
  c.series = {{"", {{3, 3e-4}}}};
  const auto status = drawOcularHazardPlot(*canvas, box, c);
  ASSERT_TRUE(status) << status.error().message;
  const Png png = fromSurface(*surface);
  const Area area = zoneExtent(png);
  // The data area takes most of the box (the rest: tick labels and axis titles).
  ASSERT_GT(area.x1 - area.x0, (box.x1 - box.x0) * 0.85);
  ASSERT_GT(area.y1 - area.y0, (box.y1 - box.y0) * 0.85);
  EXPECT_EQ(pixelAt(png, area.at(30, 3e-4)), kOcularGreenFill);
  EXPECT_EQ(pixelAt(png, area.at(3, 23)), kOcularYellowFill);
  EXPECT_EQ(pixelAt(png, area.at(3, 300)), kOcularRedFill);
  EXPECT_TRUE(colourNear(png, area.at(3, 3e-4), kInkPixel, 1, kCairoRounding));
  // Nothing outside the box.
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (x < box.x0 - 1 || x > box.x1 + 1 || y < box.y0 - 1 || y > box.y1 + 1) {
        ASSERT_EQ(png.at(x, y), kWhitePixel) << x << ", " << y;
      }
}

// Each is refused before anything is written or drawn.
TEST(OcularHazardPlot, BadContentIsRefusedWithNothingWrittenOrDrawn) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  OcularPlotContent good = emptyPlot();
  good.series = {{"array-1", {{3, 1e-3}}}, {"array-2", {{10, 1e-2}}}};
  std::vector<std::pair<std::string, OcularPlotContent>> bad;
  const auto variant = [&](const std::string& name, auto change) {
    OcularPlotContent c = good;
    change(c);
    bad.emplace_back(name, c);
  };
  variant("five series", [](auto& c) {
    for (const std::string label : {"a", "b", "c"}) c.series.push_back({label, {}});
  });
  variant("a series without a label beside another", [](auto& c) { c.series[1].label.clear(); });
  for (const double v : {0.0, -1.0, nan, inf}) {
    variant(fmt::format("angle {}", v),
            [v](auto& c) { c.series[0].points[0].subtended_angle_mrad = v; });
    variant(fmt::format("irradiance {}", v),
            [v](auto& c) { c.series[1].points[0].retinal_irradiance_w_cm2 = v; });
  }
  for (const auto& [name, content] : bad) {
    SCOPED_TRACE(name);
    glarecam::testing::TempDir dir;
    const auto status = writeOcularHazardPlot(content, dir / "ocular.png", dir / "ocular.svg");
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().code, ErrorCode::kBadInput) << status.error().message;
    EXPECT_TRUE(fs::is_empty(dir.path()));

    auto surface = render::RgbSurface::create(200, 100);
    ASSERT_TRUE(surface);
    auto canvas = render::Canvas::onSurface(*surface);
    ASSERT_TRUE(canvas);
    render::paint(*canvas, render::kWhite);
    const auto drawn = drawOcularHazardPlot(*canvas, {0, 0, 200, 100}, content);
    ASSERT_FALSE(drawn);
    EXPECT_EQ(drawn.error().code, ErrorCode::kBadInput);
    const Png png = fromSurface(*surface);
    for (int y = 0; y < png.height; ++y)
      for (int x = 0; x < png.width; ++x) ASSERT_EQ(png.at(x, y), kWhitePixel);
  }
  // The good content, one series alone without a label, and no series at all are fine.
  EXPECT_EQ(write(good).png.width, kPngWidth);
  OcularPlotContent one = good;
  one.series.pop_back();
  one.series[0].label.clear();
  EXPECT_EQ(write(one).png.width, kPngWidth);
  EXPECT_EQ(write(emptyPlot()).png.width, kPngWidth);
}

TEST(OcularHazardPlot, AnUnwritablePathIsAnErrorNotACrash) {
  glarecam::testing::TempDir dir;
  glarecam::testing::writeText(dir / "file", "not a directory");
  const OcularPlotContent c = emptyPlot();
  const auto png_failed = writeOcularHazardPlot(c, dir / "file" / "ocular.png", dir / "o.svg");
  ASSERT_FALSE(png_failed);
  EXPECT_EQ(png_failed.error().code, ErrorCode::kIo) << png_failed.error().message;
  const auto svg_failed = writeOcularHazardPlot(c, dir / "o.png", dir / "missing" / "o.svg");
  ASSERT_FALSE(svg_failed);
  EXPECT_EQ(svg_failed.error().code, ErrorCode::kIo) << svg_failed.error().message;
}

}  // namespace ocular_hazard_plot_test
}  // namespace glarecam::hazard
