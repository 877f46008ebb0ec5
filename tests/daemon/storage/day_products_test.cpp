// The day a stack belongs to: the site's mean solar day; and what a day's directory holds.
#include "daemon/storage/day_products.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>

#include "pipeline/sweep.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

TEST(DayProducts, TheDayIsTheSitesMeanSolarDay) {
  EXPECT_EQ(stackDay("20260621T101503Z-a42.30", std::nullopt), "2026-06-21");
  EXPECT_EQ(stackDay("20260621T231503Z", 7.85), "2026-06-21");    // 23:46 local mean time
  EXPECT_EQ(stackDay("20260621T234503Z", 7.85), "2026-06-22");    // 00:16
  EXPECT_EQ(stackDay("20260622T010000Z", -105.0), "2026-06-21");  // Colorado: 18:00 the day before
  EXPECT_FALSE(stackDay("alpha-40", std::nullopt));
  EXPECT_FALSE(stackDay("20261341T101503Z", std::nullopt));
}

// A glarecamd started during a day reads the day's count and sheet back; a day with no table, or
// one it cannot read, is none (the page then says none processed yet, as before).
TEST(DayProducts, ReadBackIsWhatTheDaysDirectoryHolds) {
  testing::TempDir root;
  const DayProductsOptions options{.root = root.path(), .longitude_deg = std::nullopt};
  EXPECT_FALSE(readDayProducts(options, "2026-06-21"));
  const std::filesystem::path day = root / kDaysDirectory / "2026-06-21";
  std::filesystem::create_directories(day);
  testing::writeText(day / pipeline::kSweepTableFileName, "alpha_deg,lmax\nforty,1\n");
  EXPECT_FALSE(readDayProducts(options, "2026-06-21"));

  std::filesystem::copy_file(testing::testDataDir() / "standard-module-table3.csv",
                             day / pipeline::kSweepTableFileName,
                             std::filesystem::copy_options::overwrite_existing);
  auto read = readDayProducts(options, "2026-06-21");
  ASSERT_TRUE(read);
  EXPECT_EQ(read->day, "2026-06-21");
  EXPECT_EQ(read->directory, day);
  EXPECT_EQ(read->stacks, 9u);  // Table III's rows
  EXPECT_FALSE(read->datasheet);
  EXPECT_EQ(read->detail, "9 stacks; no data sheet yet");
  testing::writeText(day / kFitsFileName, "{}");
  EXPECT_FALSE(readDayProducts(options, "2026-06-21")->datasheet);  // fits without a picture
  testing::writeText(day / kDatasheetPictureName, "\x89PNG");
  read = readDayProducts(options, "2026-06-21");
  ASSERT_TRUE(read);
  EXPECT_TRUE(read->datasheet);
  EXPECT_EQ(read->detail, "9 stacks, data sheet of an earlier run");
  EXPECT_FALSE(readDayProducts(options, "2026-06-22"));
}

}  // namespace
}  // namespace glarecam::daemon
