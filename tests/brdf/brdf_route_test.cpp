#include "brdf/brdf_route.h"

#include <gtest/gtest.h>

#include "brdf/simulated_goniophotometer.h"
#include "pipeline/contour_table.h"
#include "pipeline/glare_fits.h"
#include "pipeline/result.h"
#include "pipeline/sweep_table.h"
#include "tests/brdf/brdf_test_support.h"
#include "tests/support/test_support.h"

namespace glarecam::brdf {
namespace {

namespace fs = std::filesystem;

const surface::GaussianLobeBrdf kRouteLobe(testing::kTestLobe);

GoniophotometerOptions labOptions() {
  GoniophotometerOptions o;
  o.alphas_deg = {10, 20, 30, 40, 50};
  o.fine_step_deg = 0.2;
  o.medium_radius_deg = 20;
  o.relative_noise = 0.005;
  return o;
}

BrdfRouteOptions routeOptions(const fs::path& out) {
  BrdfRouteOptions options;
  options.output_directory = out;
  options.show_progress = false;
  options.image.max_size_px = 401;
  return options;
}

TEST(BrdfRoute, WritesResultsSweepAndContoursThatTheCameraRoutesReadersTake) {
  const glarecam::testing::TempDir dir;
  const auto files =
      writeSimulatedMeasurements(kRouteLobe, labOptions(), SimulatedFormats::kPabOpto, dir / "lab");
  ASSERT_TRUE(files) << files.error().message;
  const auto summary = runBrdfRoute(files->pabopto, routeOptions(dir / "out"));
  ASSERT_TRUE(summary) << summary.error().message;
  ASSERT_EQ(summary->angles.size(), 5u);
  const auto table = pipeline::readSweepTable(summary->sweep_csv);
  ASSERT_TRUE(table) << table.error().message;
  ASSERT_EQ(table->rows.size(), 5u);
  for (const pipeline::SweepRow& row : table->rows) {
    EXPECT_EQ(row.route, "brdf");
    EXPECT_EQ(row.reference_illuminance_lx, 100'000);
    EXPECT_TRUE(row.vertical_deg && row.horizontal_deg);
  }
  EXPECT_EQ(pipeline::tableRoutes(*table), std::vector<std::string>{"brdf"});
  const auto contours = pipeline::readContourTable(summary->contours_csv);
  ASSERT_TRUE(contours) << contours.error().message;
  EXPECT_GT(contours->rows.size(), 3u);
  const auto result = pipeline::readResult(summary->angles[1].result_directory / "result.json");
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_EQ(result->route, pipeline::Route::kBrdf);
  EXPECT_EQ(result->alpha_source, "measurement");
  EXPECT_EQ(result->brdf["noise"], "stated");
  EXPECT_TRUE(fs::exists(summary->angles[1].result_directory / "luminance.png"));
  // The fits take the table as they take the camera route's.
  const auto fits = pipeline::fitSweep(*table);
  EXPECT_TRUE(fits) << fits.error().message;
}

TEST(BrdfRoute, PabOptoAndZemaxFilesOfOneSurfaceGiveOneProfile) {
  const glarecam::testing::TempDir dir;
  const auto files =
      writeSimulatedMeasurements(kRouteLobe, labOptions(), SimulatedFormats::kBoth, dir / "lab");
  ASSERT_TRUE(files) << files.error().message;
  const auto pab = runBrdfRoute(files->pabopto, routeOptions(dir / "pab"));
  const auto zemax = runBrdfRoute({files->zemax}, routeOptions(dir / "zemax"));
  ASSERT_TRUE(pab) << pab.error().message;
  ASSERT_TRUE(zemax) << zemax.error().message;
  ASSERT_EQ(zemax->table.rows.size(), pab->table.rows.size());
  for (std::size_t i = 0; i < pab->table.rows.size(); ++i) {
    const pipeline::SweepRow &a = pab->table.rows[i], &b = zemax->table.rows[i];
    EXPECT_EQ(a.alpha_deg, b.alpha_deg);
    // Two samplings of one surface with independent 0.5 % noise: Lmax within 1 %, the axes
    // within 0.03° (the grids differ: rings vs a radial × azimuth table).
    EXPECT_NEAR(a.lmax_cd_m2, b.lmax_cd_m2, 0.01 * a.lmax_cd_m2);
    EXPECT_NEAR(*a.vertical_deg, *b.vertical_deg, 0.03);
    EXPECT_NEAR(*a.horizontal_deg, *b.horizontal_deg, 0.03);
  }
}

TEST(BrdfRoute, ARefusedFileStopsTheRunBeforeAnyPicture) {
  const glarecam::testing::TempDir dir;
  const auto files =
      writeSimulatedMeasurements(kRouteLobe, labOptions(), SimulatedFormats::kPabOpto, dir / "lab");
  ASSERT_TRUE(files);
  glarecam::testing::writeText(dir / "bad.dat",
                               "#format: theta phi BSDF\n#intheta 10\n#inphi 0\n1 0 -1\n");
  std::vector<fs::path> inputs = files->pabopto;
  inputs.push_back(dir / "bad.dat");
  const auto summary = runBrdfRoute(inputs, routeOptions(dir / "out"));
  ASSERT_FALSE(summary);
  EXPECT_EQ(summary.error().code, ErrorCode::kBadInput);
  EXPECT_NE(summary.error().message.find("bad.dat:4: negative value"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "out" / "sweep.csv"));
}

}  // namespace
}  // namespace glarecam::brdf
