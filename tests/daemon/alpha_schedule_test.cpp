// When α crosses each target as the sun moves: the crossings against a fine scan, and none when
// the sun never reaches the target.
#include "daemon/alpha_schedule.h"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "daemon/daemon_test_support.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;
using testing::utc;

TEST(AlphaSchedule, CrossingsAgreeWithAFineScan) {
  const sun::SiteLocation site{.latitude_deg = 48, .longitude_deg = 7.85, .altitude_m = 278};
  const sun::ModuleOrientation module{.tilt_deg = 24.5, .azimuth_deg = 180};
  const UtcTime from = utc("2026-06-21T00:00:00Z");
  const std::vector<double> targets{10, 45, 80};
  const auto crossings = alphaCrossings(site, module, from, 24h, targets);
  ASSERT_TRUE(crossings) << crossings.error().message;
  ASSERT_EQ(crossings->size(), 6u);  // each target morning and afternoon
  for (const AlphaCrossing& crossing : *crossings) {
    const auto at = sunIncidence(site, module, crossing.time);
    ASSERT_TRUE(at);
    EXPECT_TRUE(at->sun_up);
    // Bisected to 0.5 s, during which α moves < 0.005° (at most ~0.6°/min near sunrise).
    EXPECT_NEAR(at->alpha_deg, crossing.target_deg, 0.005);
  }
  EXPECT_FALSE((*crossings)[0].rising);
  EXPECT_TRUE((*crossings)[5].rising);
  for (std::size_t i = 1; i < crossings->size(); ++i)
    EXPECT_LT((*crossings)[i - 1].time, (*crossings)[i].time);
}

TEST(AlphaSchedule, NoCrossingWhenTheSunNeverReachesTheTarget) {
  // A north-facing vertical wall at 48° N: the sun never shines on it at α 5°.
  const sun::SiteLocation site{.latitude_deg = 48, .longitude_deg = 7.85};
  const auto crossings = alphaCrossings(site, {.tilt_deg = 90, .azimuth_deg = 0},
                                        utc("2026-12-21T00:00:00Z"), 24h, std::vector<double>{5});
  ASSERT_TRUE(crossings);
  EXPECT_TRUE(crossings->empty());
}

}  // namespace
}  // namespace glarecam::daemon
