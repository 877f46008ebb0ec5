#include "core/image_io.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <limits>

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

// The compressions libtiff brings (Debian's: libdeflate and zstd) read back exactly, and the
// header alone gives the size.
TEST(ImageIo, CompressedTiffsKeepRawValuesUnchanged) {
  for (const TiffCompression compression : {TiffCompression::kDeflate, TiffCompression::kZstd}) {
    expectRoundTrip("f.tif", ramp(40, 130, 4095), 16,
                    [&](auto path, auto& f) { return writeTiffGray16(path, f, compression); });
  }
}

TEST(ImageIo, FrameSizeComesFromTheHeaderAloneOrAClearError) {
  testing::TempDir dir;
  const RawFrame frame = ramp(37, 21, 4095);
  ASSERT_TRUE(writePngGray(dir / "f.png", frame));
  ASSERT_TRUE(writeTiffGray16(dir / "f.tif", frame, TiffCompression::kZstd));
  ASSERT_TRUE(writeTiffGray16(dir / "plain.tif", frame));
  EXPECT_LT(fs::file_size(dir / "f.tif"), fs::file_size(dir / "plain.tif"));  // compressed indeed
  for (const char* name : {"f.png", "f.tif"}) {
    auto size = readFrameSize(dir / name);
    ASSERT_TRUE(size) << size.error().message;
    EXPECT_EQ(size->width, 37) << name;
    EXPECT_EQ(size->height, 21) << name;
  }
  const std::string png = testing::readText(dir / "f.png");
  testing::writeText(dir / "short.png", png.substr(0, 20));
  std::string zero = png;
  std::fill(zero.begin() + 16, zero.begin() + 24, '\0');
  testing::writeText(dir / "zero.png", zero);
  testing::writeText(dir / "text.png", "hello");
  for (const char* name : {"short.png", "zero.png", "text.png", "missing.png"}) {
    auto size = readFrameSize(dir / name);
    ASSERT_FALSE(size) << name;
    EXPECT_EQ(size.error().code, ErrorCode::kBadInput) << name;
    EXPECT_NE(size.error().message.find(name), std::string::npos) << size.error().message;
  }
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

// Each storage and compression keeps what it promises (core/image_io.h), across 1e-3 … 1e9 (a
// glare peak's range) and NaN: FLOAT exact with both compressions (both lossless), FLOAT24 within
// a relative 2^-16 (15 mantissa bits kept, rounded), HALF within 2^-11 and infinite above 65504,
// UINT exact for integers.
TEST(ImageIo, ExrStoragesAndCompressionsKeepTheirPrecision) {
  testing::TempDir dir;
  FloatImage values(64, 9);
  for (std::size_t i = 0; i < values.pixelCount(); ++i)
    values.data()[i] = static_cast<float>(1e-3 * std::pow(10.0, 12.0 * i / values.pixelCount()) *
                                          (1 + 0.3 * std::sin(static_cast<double>(i))));
  values.data()[5] = std::numeric_limits<float>::quiet_NaN();
  FloatImage counts(64, 9);
  for (std::size_t i = 0; i < counts.pixelCount(); ++i)
    counts.data()[i] = static_cast<float>(i % 7);

  const auto roundTrip = [&](ExrStorage storage, ExrCompression compression,
                             const FloatImage& image) {
    const ExrChannel channels[] = {{"v", &image, storage}, {"n", &counts, ExrStorage::kUint}};
    EXPECT_TRUE(writeExr(dir / "x.exr", channels, compression));
    auto counted = readExr(dir / "x.exr", "n");
    EXPECT_TRUE(counted) << counted.error().message;
    if (counted) {
      for (std::size_t i = 0; i < counts.pixelCount(); ++i)
        EXPECT_EQ(counted->data()[i], counts.data()[i]);
    }
    return readExr(dir / "x.exr", "v").value();
  };
  const auto worstRelative = [&](const FloatImage& read, float below) {
    double worst = 0;
    for (std::size_t i = 0; i < values.pixelCount(); ++i) {
      const float value = values.data()[i];
      if (std::isnan(value)) {
        EXPECT_TRUE(std::isnan(read.data()[i])) << i;
      } else if (value < below) {
        worst = std::max(worst, std::abs(static_cast<double>(read.data()[i]) / value - 1));
      }
    }
    return worst;
  };
  for (const ExrCompression lossless : {ExrCompression::kZip, ExrCompression::kPiz})
    EXPECT_EQ(worstRelative(roundTrip(ExrStorage::kFloat, lossless, values), INFINITY), 0);
  const double rounded =
      worstRelative(roundTrip(ExrStorage::kFloat24, ExrCompression::kPiz, values), INFINITY);
  EXPECT_GT(rounded, 0);  // lossy indeed
  EXPECT_LE(rounded, std::ldexp(1.0, -16));
  const FloatImage halves = roundTrip(ExrStorage::kHalf, ExrCompression::kPiz, values);
  // Above half's smallest normal (6.1e-5) its 11 significant bits: 2^-11 relative.
  double worst_half = 0;
  for (std::size_t i = 0; i < values.pixelCount(); ++i) {
    const float value = values.data()[i];
    if (value > 65504) {
      EXPECT_TRUE(std::isinf(halves.data()[i])) << value;
    } else if (value > 6.2e-5f) {
      worst_half =
          std::max(worst_half, std::abs(static_cast<double>(halves.data()[i]) / value - 1));
    }
  }
  EXPECT_LE(worst_half, std::ldexp(1.0, -11));
  EXPECT_GT(worst_half, 0);

  // Integers: NaN and negatives as 0, beyond 2^32 − 1 clamped, the rest rounded.
  FloatImage odd(4, 1);
  odd.data()[0] = std::numeric_limits<float>::quiet_NaN();
  odd.data()[1] = -3;
  odd.data()[2] = 5e9f;
  odd.data()[3] = 6.6f;
  const ExrChannel odd_channel[] = {{"n", &odd, ExrStorage::kUint}};
  ASSERT_TRUE(writeExr(dir / "odd.exr", odd_channel, ExrCompression::kPiz));
  const FloatImage read = readExr(dir / "odd.exr", "n").value();
  EXPECT_EQ(read.data()[0], 0);
  EXPECT_EQ(read.data()[1], 0);
  EXPECT_EQ(read.data()[2], 4294967295.0f);
  EXPECT_EQ(read.data()[3], 7);
}

// A half channel of an odd width puts the next channel of the packed row at an odd byte: the
// integers after it are copied, not stored through an aligned pointer (UBSan in `make test`'s
// sanitizer build caught a 801-pixel quality.exr of the BRDF route doing that).
TEST(ImageIo, ChannelsAfterAnOddHalfRowKeepTheirValues) {
  const testing::TempDir dir;
  FloatImage relative(5, 3, 0.25f), counts(5, 3, 6.0f);
  counts.at(4, 2) = 3;
  const ExrChannel channels[] = {{"relative_uncertainty", &relative, ExrStorage::kHalf},
                                 {"valid_frames", &counts, ExrStorage::kUint}};
  for (ExrCompression compression : {ExrCompression::kZip, ExrCompression::kPiz}) {
    ASSERT_TRUE(writeExr(dir / "q.exr", channels, compression));
    const FloatImage read = readExr(dir / "q.exr", "valid_frames").value();
    EXPECT_EQ(read.at(0, 0), 6);
    EXPECT_EQ(read.at(4, 2), 3);
    EXPECT_EQ(readExr(dir / "q.exr", "relative_uncertainty").value().at(3, 1), 0.25f);
  }
}

// glarecam writes PNGs itself (libdeflate, one IDAT chunk): libpng, which checks every chunk's
// CRC and the zlib stream's Adler-32, reads them back pixel for pixel, at widths whose rows end
// mid-word.
TEST(ImageIo, PngsWrittenAreReadByLibpngExactly) {
  testing::TempDir dir;
  for (const int width : {1, 7, 33}) {
    const int height = 5;
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>(i * 29 + 3);
    ASSERT_TRUE(writePngRgb(dir / "colour.png", width, height, rgb));
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&image, (dir / "colour.png").c_str()))
        << image.message;
    EXPECT_EQ(image.width, static_cast<png_uint_32>(width));
    EXPECT_EQ(image.height, static_cast<png_uint_32>(height));
    EXPECT_EQ(image.format, static_cast<png_uint_32>(PNG_FORMAT_RGB));
    std::vector<std::uint8_t> read(PNG_IMAGE_SIZE(image));
    ASSERT_TRUE(png_image_finish_read(&image, nullptr, read.data(), 0, nullptr)) << image.message;
    EXPECT_EQ(read, rgb) << width;
  }
  // One flipped bit in the compressed data: the reader refuses the file (CRC), never accepts
  // other pixels.
  ASSERT_TRUE(writePngGray(dir / "f.png", ramp(33, 17, 65535)));
  std::string bytes = testing::readText(dir / "f.png");
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  testing::writeText(dir / "flipped.png", bytes);
  EXPECT_FALSE(readRawFrame(dir / "flipped.png"));
}

// Byte images (the merge's counts and flags) go into an EXR without a float copy, exactly in
// every storage.
TEST(ImageIo, ByteChannelsAreStoredExactly) {
  testing::TempDir dir;
  ByteImage counts(37, 6);
  for (std::size_t i = 0; i < counts.pixelCount(); ++i)
    counts.data()[i] = static_cast<std::uint8_t>(i * 11);
  for (const ExrStorage storage : {ExrStorage::kUint, ExrStorage::kFloat, ExrStorage::kHalf}) {
    for (const ExrCompression compression : {ExrCompression::kZip, ExrCompression::kPiz}) {
      const ExrChannel channels[] = {{"n", &counts, storage}};
      ASSERT_TRUE(writeExr(dir / "n.exr", channels, compression));
      const FloatImage read = readExr(dir / "n.exr", "n").value();
      ASSERT_TRUE(read.sameSize(counts.width(), counts.height()));
      for (std::size_t i = 0; i < counts.pixelCount(); ++i)
        ASSERT_EQ(read.data()[i], counts.data()[i]) << i;
    }
  }
  const FloatImage other_size(4, 4);
  const ExrChannel mismatched[] = {{"n", &counts, ExrStorage::kUint},
                                   {"v", &other_size, ExrStorage::kFloat}};
  const Status refused = writeExr(dir / "m.exr", mismatched);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("differ in size"), std::string::npos);
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
