// The status page's brief of a result, and the newest result an earlier run left.
#include "daemon/status/result_brief.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/json.h"
#include "support/test_support.h"
#include "tests/pipeline/result_fixture.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;

using testing::minimalResult;

TEST(ResultBrief, TakesWhatTheResultSays) {
  pipeline::StackResult result = minimalResult(5.4e5);
  result.alpha_deg = 42.3;
  result.alpha_source = "manifest";
  result.glare = true;
  result.luminance.max_method = pipeline::PeakMethod::kLowerBound;
  result.limit = {.limit_cd_m2 = 3e4,
                  .mode = pipeline::LimitMode::kAlphaCurve,
                  .status = pipeline::EllipseStatus::kTooSmall};
  const ResultBrief full = resultBrief(result);
  EXPECT_EQ(full.alpha_deg, 42.3);
  EXPECT_EQ(full.lmax_cd_m2, 5.4e5);
  EXPECT_EQ(full.lmax_bound, "lower");
  EXPECT_EQ(full.limit_cd_m2, 3e4);
  EXPECT_EQ(full.glare, true);
  const ResultBrief bare = resultBrief(minimalResult(700));
  EXPECT_FALSE(bare.alpha_deg);
  EXPECT_EQ(bare.lmax_cd_m2, 700);
  EXPECT_EQ(bare.lmax_bound, "");
  EXPECT_FALSE(bare.limit_cd_m2);
  EXPECT_FALSE(bare.glare);
}

TEST(ResultBrief, NewestIsTheGreatestIdWithAResult) {
  testing::TempDir dir;
  const fs::path results = dir / "results";
  EXPECT_FALSE(newestResult(results));  // no directory at all
  fs::create_directories(results);
  EXPECT_FALSE(newestResult(results));
  const auto write = [&](const std::string& id, const std::string& text) {
    fs::create_directories(results / id);
    testing::writeText(results / id / "result.json", text);
  };
  const auto result = [&](const std::string& id, double lmax_cd_m2) {
    write(id, jsonText(pipeline::toJson(minimalResult(lmax_cd_m2))));
  };
  result(".tmp-20260621T070000Z-a39.00-x1y2", 500);
  EXPECT_FALSE(newestResult(results));  // a result being staged is none yet
  result("zz-not-a-stack", 9);          // sorts above any time
  EXPECT_FALSE(newestResult(results));
  result("20260621T080000Z-a40.00", 1000);
  result("20260621T090000Z-a41.00", 2000);
  fs::create_directories(results / "20260621T100000Z-a42.00");  // being processed: no result yet
  result(".tmp-20260621T110000Z-a43.00-x1y2", 3000);
  testing::writeText(results / "20260621T120000Z-a44.00.failed", "bad stack\n");
  const auto newest = newestResult(results);
  ASSERT_TRUE(newest);
  EXPECT_EQ(newest->stack_id, "20260621T090000Z-a41.00");
  EXPECT_EQ(newest->directory, results / "20260621T090000Z-a41.00");
  EXPECT_EQ(newest->brief.lmax_cd_m2, 2000);
  EXPECT_FALSE(newest->images_pruned);
  // Retention pruned its images: the brief stays, the picture is known gone.
  pipeline::StackResult pruned = minimalResult(2500);
  pruned.outputs.pruned_at = "2026-06-22T10:00:00Z";
  write("20260621T095000Z-a41.50", jsonText(pipeline::toJson(pruned)));
  ASSERT_TRUE(newestResult(results));
  EXPECT_TRUE(newestResult(results)->images_pruned);
  EXPECT_EQ(newestResult(results)->brief.lmax_cd_m2, 2500);
  write("20260622T080000Z-a40.00", "{ not json");
  EXPECT_FALSE(newestResult(results));  // the newest cannot be read: none, not an older one
  // Nor one that is JSON but not a valid result (a key renamed by another tool).
  nlohmann::json renamed = pipeline::toJson(minimalResult(4000));
  renamed["luminance"]["max_cd"] = renamed["luminance"]["max_cd_m2"];
  renamed["luminance"].erase("max_cd_m2");
  write("20260622T080000Z-a40.00", renamed.dump());
  EXPECT_FALSE(newestResult(results));
}

}  // namespace
}  // namespace glarecam::daemon
