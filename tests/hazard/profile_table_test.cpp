#include "hazard/profile_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "pipeline/glare_fits.h"
#include "pipeline/glare_profile.h"
#include "pipeline/sweep_table.h"
#include "tests/hazard/hazard_fixtures.h"
#include "tests/support/test_support.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;

TEST(HazardProfileTable, ReadsTheProfileGlarecamWritesForThePapersTable) {
  // The real writer on the paper's Table III: every key the hazard needs, in the writer's format.
  pipeline::SweepTable table;
  const Result<pipeline::SweepFits> fits = pipeline::readAndFitSweep(
      glarecam::testing::testDataDir() / "standard-module-table3.csv", table, {});
  ASSERT_TRUE(fits) << fits.error().message;
  const json document = pipeline::toJson(pipeline::makeGlareProfile(
      {.module = "Standard module", .date = "2026-11-26", .source = "table3.csv"}, table, *fits,
      pipeline::inferGlareLimit(table)));
  const Result<ProfileTable> profile = ProfileTable::fromJson(document, "glare-profile.json");
  ASSERT_TRUE(profile) << profile.error().message;
  EXPECT_EQ(profile->module(), "Standard module");
  const std::vector<pipeline::ProfileRow> rows =
      pipeline::glareProfile(*fits, pipeline::inferGlareLimit(table));
  // At whole degrees the lookup returns the rows themselves.
  for (const int alpha : {5, 37, 60}) {
    const SpreadAt spread = profile->at(alpha);
    const pipeline::ProfileRow& row = rows[static_cast<std::size_t>(alpha)];
    ASSERT_EQ(spread.status, SpreadStatus::kGlare) << alpha;
    EXPECT_NEAR(*spread.vertical_deg, *row.vertical_deg, 1e-12) << alpha;
    EXPECT_NEAR(*spread.horizontal_deg, *row.horizontal_deg, 1e-12) << alpha;
    EXPECT_NEAR(*spread.circle_deg, row.beam->beta_mrad * 180 / M_PI / 1000, 1e-12) << alpha;
    EXPECT_NEAR(*profile->luminancesAt(alpha).lmax_cd_m2 / *row.lmax_cd_m2, 1, 1e-12) << alpha;
  }
  EXPECT_EQ(profile->at(80.5).status, SpreadStatus::kBeyondMethod);
}

json profileWithRows(std::function<void(json& rows)> change) {
  json document = testing::constantProfileJson(6, 4);
  change(document["profile"]);
  return document;
}

TEST(HazardProfileTable, InterpolatesAxesLinearlyAndLuminanceInLog) {
  const json document = profileWithRows([](json& rows) {
    rows[40]["vertical_deg"] = 6.0;
    rows[41]["vertical_deg"] = 8.0;
    rows[40]["lmax_cd_m2"] = 1e6;
    rows[41]["lmax_cd_m2"] = 1e4;
  });
  const ProfileTable profile = *ProfileTable::fromJson(document, "p.json");
  const SpreadAt spread = profile.at(40.25);
  EXPECT_NEAR(*spread.vertical_deg, 6.5, 1e-12);
  EXPECT_NEAR(*spread.horizontal_deg, 4.0, 1e-12);
  // ln L linear: a quarter of the way from 10⁶ to 10⁴ is 10^5.5.
  const LuminancesAt luminances = profile.luminancesAt(40.25);
  EXPECT_NEAR(*luminances.lmax_cd_m2, std::pow(10, 5.5), 1e-6);
  EXPECT_NEAR(*luminances.limit_cd_m2, 3e4, 1e-9);
  EXPECT_NEAR(*profile.at(80).vertical_deg, 6, 1e-12);  // the last row: no row above it
}

TEST(HazardProfileTable, ANullAxisTakesTheOtherRowsAndTwoNullsAreUnknown) {
  const json document = profileWithRows([](json& rows) {
    rows[30]["vertical_deg"] = nullptr;
    rows[30]["horizontal_deg"] = nullptr;
    rows[30]["circular_beam"] = nullptr;
    rows[31]["vertical_deg"] = nullptr;
    rows[31]["horizontal_deg"] = nullptr;
    rows[31]["circular_beam"] = nullptr;
  });
  const ProfileTable profile = *ProfileTable::fromJson(document, "p.json");
  EXPECT_NEAR(*profile.at(29.5).vertical_deg, 6, 1e-12);  // row 29's, row 30 has none
  const SpreadAt unknown = profile.at(30.5);
  EXPECT_EQ(unknown.status, SpreadStatus::kGlare);  // glares: never taken as "no glare"
  EXPECT_FALSE(unknown.vertical_deg);
  EXPECT_FALSE(unknown.circle_deg);
}

TEST(HazardProfileTable, AVanishingAxisCountsAsAbsent) {
  const json document = profileWithRows([](json& rows) {
    rows[50]["horizontal_deg"] = 0.0005;  // below kMinAxisDeg: no ellipse that thin
    rows[51]["horizontal_deg"] = 0.0;
  });
  const ProfileTable profile = *ProfileTable::fromJson(document, "p.json");
  EXPECT_FALSE(profile.at(50.5).horizontal_deg);
  EXPECT_NEAR(*profile.at(49.5).horizontal_deg, 4, 1e-12);  // row 49's
}

TEST(HazardProfileTable, GlaresOnlyInsideItsRangesEndsIncluded) {
  const ProfileTable profile = testing::constantProfile(6, 4, {{10, 20.5}, {30, 40}});
  EXPECT_EQ(profile.at(9.99).status, SpreadStatus::kNoGlare);
  EXPECT_EQ(profile.at(10).status, SpreadStatus::kGlare);
  EXPECT_EQ(profile.at(20.5).status, SpreadStatus::kGlare);
  EXPECT_EQ(profile.at(20.51).status, SpreadStatus::kNoGlare);
  EXPECT_EQ(profile.at(35).status, SpreadStatus::kGlare);
  EXPECT_EQ(profile.at(80).status, SpreadStatus::kNoGlare);
  EXPECT_EQ(profile.at(80.01).status, SpreadStatus::kBeyondMethod);
  // Beyond the method, the region counted is the last α's with axes (80°).
  ASSERT_TRUE(profile.lastDefined());
  EXPECT_NEAR(*profile.lastDefined()->vertical_deg, 6, 1e-12);
  EXPECT_NEAR(profile.maxFullAxisDeg(), std::max(6.0, *profile.at(35).circle_deg), 1e-12);
}

// The profile's own reader refuses what is not a profile (tests/pipeline/glare_profile_test.cpp);
// the table passes its error on.
TEST(HazardProfileTable, PassesTheReadersRefusalOn) {
  json document = testing::constantProfileJson(6, 4);
  document["profile"][3]["vertical_deg"] = "6";
  const Result<ProfileTable> profile = ProfileTable::fromJson(document, "p.json");
  ASSERT_FALSE(profile);
  EXPECT_EQ(profile.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(profile.error().message, "p.json: profile[3].vertical_deg must be a number, not \"6\"");
}

TEST(HazardProfileTable, ReadsAFileAndRefusesAMissingOne) {
  glarecam::testing::TempDir dir;
  glarecam::testing::writeText(dir / "glare-profile.json",
                               testing::constantProfileJson(6, 4).dump());
  const Result<ProfileTable> profile = ProfileTable::read(dir / "glare-profile.json");
  ASSERT_TRUE(profile) << profile.error().message;
  EXPECT_EQ(profile->path(), dir / "glare-profile.json");
  const Result<ProfileTable> missing = ProfileTable::read(dir / "none.json");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("none.json"), std::string::npos);
}

}  // namespace
}  // namespace glarecam::hazard
