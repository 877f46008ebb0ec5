// The hazard chart's files: PNG and SVG written atomically, a glaring cell's colour where its day
// and time put it (found relative to the cell panel, located in the PNG by its edge columns),
// a single glaring step still visible, the year's column (each model's hours as a bar, crossed by
// the yearly limits it exceeds), the same chart drawn into a box of a canvas and nowhere else,
// bad content refused with nothing written or drawn, and an unwritable path an error.
#include "hazard/hazard_chart.h"

#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/canvas.h"
#include "render/rgb_surface.h"
#include "support/test_support.h"

namespace glarecam::hazard {
namespace {

namespace fs = std::filesystem;

using Pixel = glarecam::testing::RgbPixel;

// The chart's documented colours (hazard_chart.h: Okabe–Ito).
constexpr Pixel kBlue{0x00, 0x72, 0xB2};        // first model only
constexpr Pixel kOrange{0xE6, 0x9F, 0x00};      // second model only
constexpr Pixel kVermillion{0xD5, 0x5E, 0x00};  // both

// An A4 landscape page at 144 dpi.
constexpr int kPngWidth = 1684, kPngHeight = 1190;

using Png = glarecam::testing::RgbPicture;

constexpr int kDays = 365;  // 2027

// A year of 2027 with the sun always up and no glare, except the first and the last day, which
// glare by both models all day: their vermillion columns mark the cell panel's edges. The
// minutes per day are zero (the chart draws what it is given).
HazardChartContent markedYear(int steps_per_day) {
  HazardChartContent c{.title = "Glare at window-3, 2027",
                       .subtitle = "test scene",
                       .year = 2027,
                       .days = kDays,
                       .steps_per_day = steps_per_day};
  c.cells.assign(static_cast<std::size_t>(kDays) * steps_per_day, HazardCell::kNone);
  for (const int day : {0, kDays - 1})
    std::fill_n(c.cells.begin() + static_cast<std::ptrdiff_t>(day) * steps_per_day, steps_per_day,
                HazardCell::kBoth);
  c.models = {{"ellipse", std::vector<double>(kDays, 0.0)},
              {"circle", std::vector<double>(kDays, 0.0)}};
  return c;
}

void setCells(HazardChartContent& c, int day, double from_h, double to_h, HazardCell cell) {
  const auto step = [&c](double h) { return static_cast<int>(h * c.steps_per_day / 24); };
  for (int s = step(from_h); s < step(to_h); ++s)
    c.cells[static_cast<std::size_t>(day) * c.steps_per_day + s] = cell;
}

// The cell panel in PNG pixels, from the extent of its vermillion edge columns (the legend's
// vermillion swatch lies inside them). Exact to the pixel or two the frame's line covers.
struct Panel {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // x1, y1 exclusive
  // Where the middle of `day` at `hour` (local time) is, on a panel showing 0–24 h.
  std::pair<int, int> at(double day, double hour) const {
    return {static_cast<int>(x0 + (day + 0.5) / kDays * (x1 - x0)),
            static_cast<int>(y1 - hour / 24 * (y1 - y0))};
  }
};

Panel findPanel(const Png& png) {
  Panel p{png.width, png.height, -1, -1};
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      if (png.at(x, y) == kVermillion) {
        p.x0 = std::min(p.x0, x);
        p.y0 = std::min(p.y0, y);
        p.x1 = std::max(p.x1, x + 1);
        p.y1 = std::max(p.y1, y + 1);
      }
  return p;
}

// Whether `colour` is at some pixel within `radius` of (x, y).
bool colourNear(const Png& png, std::pair<int, int> at, const Pixel& colour, int radius) {
  for (int y = at.second - radius; y <= at.second + radius; ++y)
    for (int x = at.first - radius; x <= at.first + radius; ++x)
      if (x >= 0 && y >= 0 && x < png.width && y < png.height && png.at(x, y) == colour)
        return true;
  return false;
}

struct Written {
  Png png;
  std::string svg;
};

Written write(const HazardChartContent& content) {
  glarecam::testing::TempDir dir;
  const auto status = writeHazardChart(content, dir / "chart.png", dir / "chart.svg");
  EXPECT_TRUE(status) << status.error().message;
  if (!status) return {};
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_NE(entry.path().filename().string().rfind(".tmp-", 0), 0u) << entry.path();
  return {glarecam::testing::readPngRgb(dir / "chart.png"),
          glarecam::testing::readText(dir / "chart.svg")};
}

TEST(HazardChart, WritesAPngPageAndAnSvgDocument) {
  const Written written = write(markedYear(1440));
  EXPECT_EQ(written.png.width, kPngWidth);
  EXPECT_EQ(written.png.height, kPngHeight);
  EXPECT_NE(written.svg.find("<svg"), std::string::npos);
  EXPECT_NE(written.svg.find("</svg>"), std::string::npos);
}

TEST(HazardChart, AGlaringCellShowsInItsModelsColourAtItsDayAndTime) {
  HazardChartContent c = markedYear(1440);
  setCells(c, 100, 18.4, 18.6, HazardCell::kFirstOnly);  // 12 steps on 11 April
  setCells(c, 250, 7.0, 7.2, HazardCell::kSecondOnly);   // 8 September
  const Png png = write(c).png;
  const Panel panel = findPanel(png);
  // The panel spans most of the page's width (365 days over ~750 pt, 2 px a point).
  ASSERT_GT(panel.x1 - panel.x0, kPngWidth * 3 / 4);
  ASSERT_GT(panel.y1 - panel.y0, kPngHeight / 3);
  // A day is about 4 px wide, 0.2 h about 5 px tall: 2 px covers the frame's edge error.
  constexpr int kRadius = 2;
  EXPECT_TRUE(colourNear(png, panel.at(100, 18.5), kBlue, kRadius));
  EXPECT_TRUE(colourNear(png, panel.at(250, 7.1), kOrange, kRadius));
  EXPECT_FALSE(colourNear(png, panel.at(100, 12.0), kBlue, kRadius));
  EXPECT_FALSE(colourNear(png, panel.at(250, 18.5), kOrange, kRadius));
}

// A mark (SIMULATED) goes over everything, the opaque cell panel too, as translucent red: the
// panel's white cells under it turn the pale red of the data sheet's mark, and glare still shows.
TEST(HazardChart, AMarkCrossesThePageOverTheCells) {
  HazardChartContent c = markedYear(1440);
  const Png plain = write(c).png;
  c.mark = "SIMULATED";
  c.mark_note = "stacks of the simulated camera: not a measurement";
  const Png marked = write(c).png;
  const Panel panel = findPanel(marked);
  ASSERT_GT(panel.x1 - panel.x0, kPngWidth * 3 / 4);
  // White (1, 1, 1) under red at 22 % opacity: (255, 199, 199), within rounding.
  const auto pale = [](const Pixel& p) {
    return p[0] == 255 && p[1] >= 196 && p[1] <= 201 && p[2] == p[1];
  };
  std::size_t pale_in_panel = 0, pale_before = 0;
  for (int y = panel.y0 + 2; y < panel.y1 - 2; ++y) {
    for (int x = panel.x0 + 2; x < panel.x1 - 2; ++x) {
      pale_in_panel += pale(marked.at(x, y)) ? 1 : 0;
      pale_before += pale(plain.at(x, y)) ? 1 : 0;
    }
  }
  EXPECT_EQ(pale_before, 0u);
  // The 120-pt letters cover tens of thousands of the panel's pixels.
  EXPECT_GT(pale_in_panel, 10000u);
  // The glaring first and last days still show through it at their edges.
  EXPECT_EQ(marked.at(panel.x0 + 1, (panel.y0 + panel.y1) / 2), kVermillion);
}

// At 10-s steps a pixel row of the panel aggregates some 15 steps: one glaring step among them
// still colours it (glare wins), and so does one among sun-down steps.
TEST(HazardChart, ASingleGlaringStepStillShows) {
  for (const int steps_per_day : {1440, 8640}) {
    SCOPED_TRACE(steps_per_day);
    HazardChartContent c = markedYear(steps_per_day);
    const int noon = steps_per_day / 2;
    c.cells[static_cast<std::size_t>(180) * steps_per_day + noon] = HazardCell::kFirstOnly;
    setCells(c, 200, 20.0, 21.0, HazardCell::kSunDown);
    c.cells[static_cast<std::size_t>(200) * steps_per_day + noon * 41 / 24] =
        HazardCell::kFirstOnly;  // 20:30
    const Png png = write(c).png;
    const Panel panel = findPanel(png);
    EXPECT_TRUE(colourNear(png, panel.at(180, 12.0), kBlue, 2));
    EXPECT_TRUE(colourNear(png, panel.at(200, 20.5), kBlue, 2));
  }
}

// Each is refused before anything is written.
TEST(HazardChart, BadContentIsRefusedWithNothingWritten) {
  const HazardChartContent good = markedYear(24);
  std::vector<std::pair<std::string, HazardChartContent>> bad;
  const auto variant = [&](const std::string& name, auto change) {
    HazardChartContent c = good;
    change(c);
    bad.emplace_back(name, c);
  };
  variant("a cell missing", [](auto& c) { c.cells.pop_back(); });
  variant("364 days", [](auto& c) {
    c.days = 364;
    c.cells.resize(364 * 24);
  });
  variant("366 days in 2027", [](auto& c) {
    c.days = 366;
    c.cells.resize(366 * 24, HazardCell::kNone);
    for (auto& m : c.models) m.minutes_per_day.resize(366);
  });
  variant("no steps", [](auto& c) {
    c.steps_per_day = 0;
    c.cells.clear();
  });
  variant("no model", [](auto& c) { c.models.clear(); });
  variant("three models", [](auto& c) { c.models.push_back(c.models[0]); });
  variant("a short series", [](auto& c) { c.models[1].minutes_per_day.pop_back(); });
  variant("negative minutes", [](auto& c) { c.models[0].minutes_per_day[3] = -1; });
  variant("no threshold", [](auto& c) { c.threshold_minutes_per_day = 0; });
  variant("not a cell", [](auto& c) { c.cells[100] = static_cast<HazardCell>(9); });
  variant("a second model's glare with one model", [](auto& c) { c.models.pop_back(); });
  variant("a yearly limit of 0 h", [](auto& c) { c.yearly_limits = {{"LAI", 0}}; });
  variant("a yearly limit without a label", [](auto& c) { c.yearly_limits = {{"", 30}}; });
  for (const auto& [name, content] : bad) {
    SCOPED_TRACE(name);
    glarecam::testing::TempDir dir;
    const auto status = writeHazardChart(content, dir / "chart.png", dir / "chart.svg");
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().code, ErrorCode::kBadInput) << status.error().message;
    EXPECT_TRUE(fs::is_empty(dir.path()));
  }
  // One model alone, its glare as the first's, is fine.
  HazardChartContent one = good;
  one.models.pop_back();
  for (HazardCell& cell : one.cells)
    if (cell == HazardCell::kBoth) cell = HazardCell::kFirstOnly;
  EXPECT_EQ(write(one).png.width, kPngWidth);
}

// The first model's bar in the year's column: the extent of its blue right of the cell panel.
struct Bar {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // x1, y1 exclusive
  bool found() const { return x1 > x0 && y1 > y0; }
};

Bar findBar(const Png& png, int right_of) {
  Bar bar{png.width, png.height, -1, -1};
  for (int y = 0; y < png.height; ++y)
    for (int x = right_of; x < png.width; ++x)
      if (png.at(x, y) == kBlue) {
        bar.x0 = std::min(bar.x0, x);
        bar.y0 = std::min(bar.y0, y);
        bar.x1 = std::max(bar.x1, x + 1);
        bar.y1 = std::max(bar.y1, y + 1);
      }
  return bar;
}

// Runs of pixel rows inside the bar crossed by dark ink: the yearly limits below its top.
int limitsCrossing(const Png& png, const Bar& bar) {
  const auto dark = [](const Pixel& p) { return p[0] < 100 && p[1] < 100 && p[2] < 100; };
  int runs = 0;
  bool in_run = false;
  for (int y = bar.y0; y < bar.y1; ++y) {
    bool crossed = false;
    for (int x = bar.x0; x < bar.x1 && !crossed; ++x) crossed = dark(png.at(x, y));
    runs += crossed && !in_run ? 1 : 0;
    in_run = crossed;
  }
  return runs;
}

TEST(HazardChart, TheYearsColumnSetsEachModelsHoursAgainstTheYearlyLimits) {
  HazardChartContent c = markedYear(24);
  // Without limits, no column: nothing blue right of the cell panel.
  {
    const Png png = write(c).png;
    EXPECT_FALSE(findBar(png, findPanel(png).x1 + 2).found());
  }
  c.yearly_limits = {{"LAI", 30}, {"CH", 50}};
  // 10 min a day by the first model: 60.8 h, above both limits; 6.5 min a day: 39.5 h, above
  // LAI's only.
  for (const auto& [minutes_per_day, crossings] : {std::pair{10.0, 2}, std::pair{6.5, 1}}) {
    SCOPED_TRACE(minutes_per_day);
    c.models[0].minutes_per_day.assign(kDays, minutes_per_day);
    const Png png = write(c).png;
    const Panel panel = findPanel(png);
    // The panels make room for the column, still most of the page wide.
    EXPECT_GT(panel.x1 - panel.x0, kPngWidth * 2 / 3);
    EXPECT_LT(panel.x1, kPngWidth - 150);
    const Bar bar = findBar(png, panel.x1 + 2);
    ASSERT_TRUE(bar.found());
    EXPECT_GT(bar.y1 - bar.y0, 100);
    EXPECT_EQ(limitsCrossing(png, bar), crossings);
  }
}

// The chart drawn into a box of a canvas, as a report page embeds it: the panels inside the box,
// nothing outside it; refused content draws nothing.
TEST(HazardChart, DrawnIntoABoxOfACanvasAndNowhereElse) {
  constexpr int kWidth = 900, kHeight = 560;
  const render::Box box{40, 30, 860, 530};
  const auto draw = [&](const HazardChartContent& c, Status& status) {
    render::RgbSurface surface = render::RgbSurface::create(kWidth, kHeight).value();
    render::Canvas canvas = render::Canvas::onSurface(surface).value();
    render::paint(canvas, render::kWhite);
    status = drawHazardChart(canvas, box, c);
    const render::RgbImage image = surface.copyRgb();
    return Png{image.width, image.height, image.rgb};
  };
  HazardChartContent c = markedYear(1440);
  c.yearly_limits = {{"LAI", 30}};
  Status status;
  const Png png = draw(c, status);
  ASSERT_TRUE(status) << status.error().message;
  const Panel panel = findPanel(png);
  EXPECT_GE(panel.x0, box.x0);
  EXPECT_LE(panel.x1, box.x1);
  EXPECT_GT(panel.x1 - panel.x0, (box.x1 - box.x0) / 2);
  // One pixel of slack: a line on the box's edge is anti-aliased across it.
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (x < box.x0 - 1 || x > box.x1 + 1 || y < box.y0 - 1 || y > box.y1 + 1) {
        ASSERT_EQ(png.at(x, y), (Pixel{255, 255, 255})) << x << ", " << y;
      }
    }
  }

  c.models.clear();
  const Png refused = draw(c, status);
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(findPanel(refused).x1, -1);
}

TEST(HazardChart, AnUnwritablePathIsAnErrorNotACrash) {
  glarecam::testing::TempDir dir;
  glarecam::testing::writeText(dir / "file", "not a directory");
  const HazardChartContent c = markedYear(24);
  const auto png_failed = writeHazardChart(c, dir / "file" / "chart.png", dir / "chart.svg");
  ASSERT_FALSE(png_failed);
  EXPECT_EQ(png_failed.error().code, ErrorCode::kIo) << png_failed.error().message;
  const auto svg_failed = writeHazardChart(c, dir / "chart.png", dir / "missing" / "chart.svg");
  ASSERT_FALSE(svg_failed);
  EXPECT_EQ(svg_failed.error().code, ErrorCode::kIo) << svg_failed.error().message;
}

}  // namespace
}  // namespace glarecam::hazard
