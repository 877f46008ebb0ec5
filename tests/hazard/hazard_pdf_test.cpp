// The hazard report's PDF: one file of A4 landscape pages written atomically, two pages per
// pictured receptor (an observer, a route's worst point) after the scene, results and method
// pages; a scene with routes, obstructions and a simulated profile drawn as well; an incomplete
// report or a partial year refused with nothing written; an unwritable path a kIo error naming it,
// with what was there left as it was. What the pages say is read back by the CLI test
// (tests/apps/hazard_cli_test.sh, pdftotext and pdftoppm).
#include "hazard/hazard_pdf.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "hazard/hazard_calculation.h"
#include "hazard/hazard_report.h"
#include "hazard/obstruction.h"
#include "tests/hazard/hazard_fixtures.h"
#include "tests/support/test_support.h"

namespace glarecam::hazard {
// Named after the file: in a unity build the test files share translation units.
namespace hazard_pdf_test {

namespace fs = std::filesystem;

// The docs' example roof (docs/examples/hazard-scene.json): faces north, tilted 30°.
ArrayPolygon exampleRoof() {
  return *makeArrayPolygon("roof-north", {{-6, 0, 9}, {6, 0, 9}, {6, 5.2, 6}, {-6, 5.2, 6}},
                           "scene.json", "arrays[0].vertices_m");
}

Observer observerAt(const std::string& name, Vec3 position_m) {
  return {.name = name, .position_m = position_m, .from_h = 6, .to_h = 22};
}

// A whole year at hourly steps (the report's charts need every day): quick, and glare enough.
struct Computed {
  Scene scene;
  ProfileTable profile = testing::constantProfile(4, 2);
  HazardOptions options;
  HazardResult result;

  explicit Computed(Scene s, bool simulated = false) : scene(std::move(s)) {
    if (simulated) {
      nlohmann::json document = testing::constantProfileJson(4, 2);
      document["simulated"] = true;
      profile = *ProfileTable::fromJson(document, "simulated.json");
    }
    options.year = 2027;
    options.step_s = 3600;
    options.models = {{ModelKind::kEllipse}, {ModelKind::kCircle}};
    result = *computeHazard(scene, {&profile}, options);
  }

  HazardReport report() const {
    return {.scene = &scene,
            .profiles = {&profile},
            .options = &options,
            .result = &result,
            .picture_stems = pictureStems(scene, result),
            .daylight_saving = DaylightSaving::kEu};
  }
};

Scene observersScene(int count) {
  std::vector<Observer> observers;
  for (int i = 0; i < count; ++i)
    observers.push_back(observerAt("window-" + std::to_string(i + 1), {-10.0 * i, 30, 12}));
  return testing::sceneOf(testing::zurichSite(), {exampleRoof()}, observers);
}

TEST(HazardPdf, TwoPagesPerPicturedReceptorAfterTheFrontPages) {
  glarecam::testing::TempDir dir;
  const Computed two(observersScene(2)), three(observersScene(3));
  ASSERT_TRUE(writeHazardReportPdf(two.report(), dir / "two.pdf"));
  ASSERT_TRUE(writeHazardReportPdf(three.report(), dir / "three.pdf"));
  EXPECT_EQ(glarecam::testing::readText(dir / "two.pdf").rfind("%PDF-", 0), 0u);
  const int pages = glarecam::testing::pdfPageCount(dir / "two.pdf");
  // The scene, the results and at least one page of the method, then two per receptor.
  EXPECT_GE(pages, 3 + 2 * 2);
  EXPECT_EQ(glarecam::testing::pdfPageCount(dir / "three.pdf"), pages + 2);
  EXPECT_TRUE(glarecam::testing::noTemporaryFiles(dir.path()));
}

// Routes, obstructions (extruded and planar), an observer facing away and a simulated profile:
// every part of the plan and the SIMULATED mark are drawn, and a route's worst point alone gets
// its pages.
TEST(HazardPdf, ASceneWithRoutesAndObstructionsIsDrawn) {
  Scene scene = observersScene(1);
  scene.observers[0].view_azimuths_deg = {180};
  scene.observers[0].field_of_view_deg = 90;
  const std::size_t first = scene.observers.size();
  for (int i = 0; i < 3; ++i) {
    Observer point = observerAt("road@" + std::to_string(20 * i) + "m", {-20.0 + 20 * i, 40, 1.1});
    point.view_azimuths_deg = {90};
    point.field_of_view_deg = 50;
    point.receptor = scene.receptors.size();
    scene.observers.push_back(point);
  }
  scene.receptors.push_back(
      {.kind = ReceptorKind::kRoute, .name = "road", .first = first, .count = 3});
  scene.obstructions.push_back(
      *makeExtrudedObstruction("house", {{{20, 20}}, {{30, 20}}, {{30, 30}}, {{20, 30}}}, 0, 8,
                               "scene.json", "obstructions[0]"));
  scene.obstructions.push_back(
      *makePlanarObstruction("wall", {{-20, 5, 0}, {-20, 15, 0}, {-20, 15, 3}, {-20, 5, 3}},
                             "scene.json", "obstructions[1]"));
  const Computed computed(scene, /*simulated=*/true);
  glarecam::testing::TempDir dir;
  const auto written = writeHazardReportPdf(computed.report(), dir / "report.pdf");
  ASSERT_TRUE(written) << written.error().message;
  // One observer and the road's worst point: four receptor pages after the front pages.
  EXPECT_GE(glarecam::testing::pdfPageCount(dir / "report.pdf"), 3 + 2 * 2);
  EXPECT_EQ(computed.report().picture_stems[first + 1], "");
}

TEST(HazardPdf, AnIncompleteReportOrAPartialYearIsRefusedWithNothingWritten) {
  glarecam::testing::TempDir dir;
  const Computed computed(observersScene(1));
  HazardReport no_result = computed.report();
  no_result.result = nullptr;
  HazardReport no_pictures = computed.report();
  no_pictures.picture_stems.clear();
  for (const HazardReport& bad : {no_result, no_pictures}) {
    const auto status = writeHazardReportPdf(bad, dir / "report.pdf");
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().code, ErrorCode::kBadInput) << status.error().message;
  }
  // The charts show a whole year: a preview of 30 days has none to show.
  Computed partial(observersScene(1));
  partial.options.day_count = 30;
  partial.result = *computeHazard(partial.scene, {&partial.profile}, partial.options);
  const auto status = writeHazardReportPdf(partial.report(), dir / "report.pdf");
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kBadInput) << status.error().message;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(HazardPdf, AnUnwritablePathIsAnErrorNamingItAndLeavesWhatWasThere) {
  glarecam::testing::TempDir dir;
  glarecam::testing::writeText(dir / "file", "not a directory");
  const Computed computed(observersScene(1));
  const fs::path under_a_file = dir / "file" / "report.pdf";
  const auto failed = writeHazardReportPdf(computed.report(), under_a_file);
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().code, ErrorCode::kIo) << failed.error().message;
  EXPECT_NE(failed.error().message.find(under_a_file.string()), std::string::npos)
      << failed.error().message;
  // A directory where the file should go: refused, and the directory stays.
  fs::create_directory(dir / "taken.pdf");
  const auto taken = writeHazardReportPdf(computed.report(), dir / "taken.pdf");
  ASSERT_FALSE(taken);
  EXPECT_EQ(taken.error().code, ErrorCode::kIo) << taken.error().message;
  EXPECT_TRUE(fs::is_directory(dir / "taken.pdf"));
  // An old report is replaced whole, or not at all.
  glarecam::testing::writeText(dir / "old.pdf", "an old report");
  HazardReport bad = computed.report();
  bad.options = nullptr;
  ASSERT_FALSE(writeHazardReportPdf(bad, dir / "old.pdf"));
  EXPECT_EQ(glarecam::testing::readText(dir / "old.pdf"), "an old report");
  ASSERT_TRUE(writeHazardReportPdf(computed.report(), dir / "old.pdf"));
  EXPECT_EQ(glarecam::testing::readText(dir / "old.pdf").rfind("%PDF-", 0), 0u);
  EXPECT_TRUE(glarecam::testing::noTemporaryFiles(dir.path()));
}

}  // namespace hazard_pdf_test
}  // namespace glarecam::hazard
