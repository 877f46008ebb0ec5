#include "core/image_io.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_support.h"

namespace glarecam {
namespace {

RawFrame ramp(int width, int height, int max_value) {
  RawFrame frame(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) frame.at(x, y) = static_cast<std::uint16_t>((x * 37 + y * 101) % (max_value + 1));
  }
  return frame;
}

void expectEqual(const RawFrame& a, const RawFrame& b) {
  ASSERT_TRUE(a.sameSize(b.width(), b.height()));
  for (std::size_t i = 0; i < a.pixelCount(); ++i) ASSERT_EQ(a.data()[i], b.data()[i]) << "pixel " << i;
}

TEST(ImageIo, Png16KeepsRawValuesUnchanged) {
  testing::TempDir dir;
  const RawFrame frame = ramp(33, 17, 65535);
  ASSERT_TRUE(writePngGray(dir / "f.png", frame));
  auto read = readRawFrame(dir / "f.png");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->bit_depth, 16);
  expectEqual(read->pixels, frame);
}

TEST(ImageIo, Png8IsWidenedNotScaled) {
  testing::TempDir dir;
  const RawFrame frame = ramp(20, 11, 255);
  ASSERT_TRUE(writePngGray(dir / "f.png", frame, 8));
  auto read = readRawFrame(dir / "f.png");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->bit_depth, 8);
  expectEqual(read->pixels, frame);
}

TEST(ImageIo, Tiff16KeepsRawValuesUnchanged) {
  testing::TempDir dir;
  const RawFrame frame = ramp(40, 130, 4095);  // more rows than one strip
  ASSERT_TRUE(writeTiffGray16(dir / "f.tif", frame));
  auto read = readRawFrame(dir / "f.tif");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->bit_depth, 16);
  expectEqual(read->pixels, frame);
}

TEST(ImageIo, ExrRoundTripsFloats) {
  testing::TempDir dir;
  FloatImage image(19, 7);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) image.data()[i] = static_cast<float>(std::pow(10.0, i % 9)) * 1.2345f;
  ASSERT_TRUE(writeExr(dir / "l.exr", image));
  auto read = readExr(dir / "l.exr");
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_TRUE(read->sameSize(19, 7));
  for (std::size_t i = 0; i < image.pixelCount(); ++i) EXPECT_EQ(read->data()[i], image.data()[i]);
}

TEST(ImageIo, ColourPngIsRefusedWithItsName) {
  testing::TempDir dir;
  std::vector<std::uint8_t> rgb(8 * 4 * 3, 128);
  ASSERT_TRUE(writePngRgb(dir / "colour.png", 8, 4, rgb));
  auto read = readRawFrame(dir / "colour.png");
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
  EXPECT_NE(read.error().message.find("colour.png: is not a single-channel"), std::string::npos) << read.error().message;
}

TEST(ImageIo, EveryTruncationOfAPngIsAnErrorNotACrash) {
  testing::TempDir dir;
  ASSERT_TRUE(writePngGray(dir / "f.png", ramp(24, 16, 65535)));
  const std::string bytes = testing::readText(dir / "f.png");
  for (std::size_t length = 0; length < bytes.size(); length += 7) {
    testing::writeText(dir / "cut.png", bytes.substr(0, length));
    auto read = readRawFrame(dir / "cut.png");
    EXPECT_FALSE(read) << "truncated to " << length << " bytes was accepted";
  }
}

}  // namespace
}  // namespace glarecam
