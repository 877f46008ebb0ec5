// A sweep's fits in one call, for the tests of what is made from them (the glare profile, the data
// sheet).
#pragma once

#include <gtest/gtest.h>

#include "pipeline/glare_fits.h"
#include "pipeline/sweep_table.h"

namespace glarecam::testing {

// The fits of `table`; fails the calling test when there are none.
inline pipeline::SweepFits fitsOf(const pipeline::SweepTable& table) {
  auto fits = pipeline::fitSweep(table);
  EXPECT_TRUE(fits) << fits.error().message;
  return *fits;
}

}  // namespace glarecam::testing
