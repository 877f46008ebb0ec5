#include "core/spelling.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace glarecam {
namespace {

TEST(Spelling, EditDistanceCountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(editDistance("", ""), 0u);
  EXPECT_EQ(editDistance("threshold", "threshold"), 0u);
  EXPECT_EQ(editDistance("threshhold", "threshold"), 1u);  // insertion
  EXPECT_EQ(editDistance("treshold", "threshold"), 1u);    // deletion
  EXPECT_EQ(editDistance("thresjold", "threshold"), 1u);   // substitution
  EXPECT_EQ(editDistance("thresohld", "threshold"), 1u);   // swap of neighbours
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
}

TEST(Spelling, SuggestsTheClosestKnownNameOnlyWhenItIsClose) {
  const std::vector<std::string> options{"--threshold", "--thresholds", "--out", "--alpha",
                                         "--calibration"};
  EXPECT_EQ(closestSpelling("--threshhold", options), "--threshold");
  EXPECT_EQ(closestSpelling("--aplha", options), "--alpha");
  EXPECT_EQ(closestSpelling("--calib", options), "--calibration");  // the only one it begins
  EXPECT_EQ(closestSpelling("--output", options), "--out");         // 3 edits, but it begins so
  EXPECT_EQ(closestSpelling("--zebra", options), std::nullopt);
  EXPECT_EQ(closestSpelling("--thr", options), std::nullopt);  // begins two: no guess
  EXPECT_EQ(closestSpelling("", options), std::nullopt);
  EXPECT_EQ(closestSpelling("x", {}), std::nullopt);
}

}  // namespace
}  // namespace glarecam
