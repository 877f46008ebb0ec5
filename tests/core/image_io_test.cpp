#include "core/image_io.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_support.h"

namespace glarecam {
namespace {

RawFrame ramp(int width, int height, int max_value) {
  RawFrame frame(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      frame.at(x, y) = static_cast<std::uint16_t>((x * 37 + y * 101) % (max_value + 1));
  }
  return frame;
}

// Writes `frame` with `write`, reads it back, and checks the values and the file's bit depth.
template <typename Write>
void expectRoundTrip(const std::string& name, const RawFrame& frame, int bit_depth, Write write) {
  testing::TempDir dir;
  ASSERT_TRUE(write(dir / name, frame));
  auto read = readRawFrame(dir / name);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->bit_depth, bit_depth);
  ASSERT_TRUE(read->pixels.sameSize(frame.width(), frame.height()));
  for (std::size_t i = 0; i < frame.pixelCount(); ++i)
    ASSERT_EQ(read->pixels.data()[i], frame.data()[i]) << "pixel " << i;
}

TEST(ImageIo, Png16KeepsRawValuesUnchanged) {
  expectRoundTrip("f.png", ramp(33, 17, 65535), 16,
                  [](auto path, auto& f) { return writePngGray(path, f); });
}

TEST(ImageIo, Png8IsWidenedNotScaled) {
  expectRoundTrip("f.png", ramp(20, 11, 255), 8,
                  [](auto path, auto& f) { return writePngGray(path, f, 8); });
}

TEST(ImageIo, Tiff16KeepsRawValuesUnchanged) {
  // More rows than one strip.
  expectRoundTrip("f.tif", ramp(40, 130, 4095), 16,
                  [](auto path, auto& f) { return writeTiffGray16(path, f); });
}

TEST(ImageIo, ExrRoundTripsFloats) {
  testing::TempDir dir;
  FloatImage image(19, 7);
  for (std::size_t i = 0; i < image.pixelCount(); ++i)
    image.data()[i] = static_cast<float>(std::pow(10.0, i % 9)) * 1.2345f;
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
  EXPECT_NE(read.error().message.find("colour.png: is not a single-channel"), std::string::npos)
      << read.error().message;
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
