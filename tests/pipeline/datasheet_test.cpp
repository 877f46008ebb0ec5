// The data sheet files: PDF, SVG and PNG written atomically, and a missing directory an error.
#include "pipeline/datasheet.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>

#include "pipeline/sweep_fits_test_support.h"
#include "pipeline/sweep_table.h"
#include "support/test_support.h"

namespace glarecam::pipeline {
namespace {

using testing::fitsOf;

TEST(Datasheet, WritesPdfSvgAndPng) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  testing::TempDir dir;
  auto status = writeDatasheet({.module = "standard",
                                .date = "2026-11-26",
                                .table = &*table,
                                .fits = &fits,
                                .model_beta_deg = 1.25,
                                .limit = {.constant_cd_m2 = 30000}},
                               dir.path());
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_EQ(testing::readText(dir / kDatasheetPdf).substr(0, 5), "%PDF-");
  const std::string svg = testing::readText(dir / kDatasheetSvg);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(testing::readText(dir / kDatasheetPng).substr(1, 3), "PNG");
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_NE(entry.path().filename().string().rfind(".tmp-", 0), 0u) << entry.path();
}

// Stacks of the simulated camera mark the sheet's face (and name the camera in the subtitle): the
// same table drawn with and without a "sim" row differs.
TEST(Datasheet, ASimulatedSweepIsMarkedOnTheSheet) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  testing::TempDir dir;
  const auto draw = [&](const SweepTable& drawn, const std::filesystem::path& out) {
    std::filesystem::create_directories(out);
    auto status = writeDatasheet({.module = "standard",
                                  .date = "2026-11-26",
                                  .table = &drawn,
                                  .fits = &fits,
                                  .model_beta_deg = std::nullopt,
                                  .limit = {}},
                                 out);
    EXPECT_TRUE(status) << status.error().message;
    return testing::readText(out / kDatasheetPng);
  };
  const std::string plain = draw(*table, dir / "plain");
  EXPECT_EQ(draw(*table, dir / "again"), plain);  // drawing is deterministic
  SweepTable simulated = *table;
  for (SweepRow& row : simulated.rows) row.camera_backend = "sim";
  ASSERT_TRUE(isSimulated(simulated));
  EXPECT_FALSE(isSimulated(*table));
  EXPECT_NE(draw(simulated, dir / "simulated"), plain);
}

// α in the table is rounded to its own uncertainty (4.99985 ± 0.05° is "5.00", not "4.99985"),
// to 0.1° when the row records none.
TEST(Datasheet, AlphaIsShownToItsOwnUncertainty) {
  SweepTable table;
  table.rows.resize(2);
  for (SweepRow& row : table.rows) {
    row.limit_cd_m2 = 30000;
    row.lmax_cd_m2 = 5e5;
  }
  table.rows[0].alpha_deg = 4.99985;
  table.rows[0].alpha_uncertainty_deg = 0.05;
  table.rows[1].alpha_deg = 10.0432;
  const render::TextTable cells = datasheetSweepTable(table);
  ASSERT_EQ(cells.rows.size(), 3u);
  EXPECT_EQ(cells.rows[1][0], "5.00");
  EXPECT_EQ(cells.rows[2][0], "10.0");
}

TEST(Datasheet, MissingDirectoryIsAnErrorNotACrash) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  auto status = writeDatasheet({.module = "m",
                                .date = "d",
                                .table = &*table,
                                .fits = &fits,
                                .model_beta_deg = std::nullopt,
                                .limit = {}},
                               "/nonexistent/dir");
  EXPECT_FALSE(status);
}

}  // namespace
}  // namespace glarecam::pipeline
