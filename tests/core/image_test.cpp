#include "core/image.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace glarecam {
namespace {

TEST(Image, ANewImageIsFilledAndAnUninitializedOneHasItsSize) {
  const FloatImage filled(31, 7, 2.5f);
  EXPECT_TRUE(std::all_of(filled.data(), filled.data() + filled.pixelCount(),
                          [](float v) { return v == 2.5f; }));
  const RawFrame zeros(5, 3);
  EXPECT_TRUE(std::all_of(zeros.data(), zeros.data() + zeros.pixelCount(),
                          [](std::uint16_t v) { return v == 0; }));

  RawFrame raw = RawFrame::uninitialized(640, 480);
  EXPECT_TRUE(raw.sameSize(640, 480));
  ASSERT_EQ(raw.pixelCount(), 640u * 480u);
  for (int y = 0; y < raw.height(); ++y)
    std::fill(raw.row(y).begin(), raw.row(y).end(), static_cast<std::uint16_t>(y));
  EXPECT_EQ(raw.at(639, 479), 479);
  const RawFrame copy = raw;  // copies like any image
  EXPECT_EQ(copy.at(3, 17), 17);
}

}  // namespace
}  // namespace glarecam
