#include "core/exr_zip.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>
#include <half.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <random>

#include "core/atomic_file.h"
#include "core/parallel.h"
#include "support/test_support.h"

namespace glarecam {
namespace {

template <typename T>
ExrZipChannel channelOf(std::string name, ExrPixelType type, const std::vector<T>& pixels,
                        int width) {
  return {std::move(name), type, [&pixels, width](int y, std::byte* out) {
            std::memcpy(out, pixels.data() + static_cast<std::size_t>(y) * width,
                        sizeof(T) * static_cast<std::size_t>(width));
          }};
}

// Reads channel `name` of `path` through OpenEXR itself, as T.
template <typename T>
std::vector<T> readChannel(const std::filesystem::path& path, const char* name, Imf::PixelType type,
                           int width, int height) {
  Imf::InputFile file(path.c_str());
  EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
  const Imath::Box2i window = file.header().dataWindow();
  EXPECT_EQ(window.max.x - window.min.x + 1, width);
  EXPECT_EQ(window.max.y - window.min.y + 1, height);
  EXPECT_EQ(file.header().channels().findChannel(name)->type, type);
  std::vector<T> pixels(static_cast<std::size_t>(width) * height);
  Imf::FrameBuffer buffer;
  buffer.insert(
      name, Imf::Slice(type, reinterpret_cast<char*>(pixels.data()), sizeof(T), sizeof(T) * width));
  file.setFrameBuffer(buffer);
  file.readPixels(0, height - 1);
  return pixels;
}

// Every pixel type in one file, over several chunks of 16 lines and a partial last one, written by
// one thread and by three: OpenEXR reads every value back bit for bit. The top rows are random
// floats (a chunk deflate cannot shrink, stored as it is), the rest smooth (compressed).
TEST(ExrZip, OpenExrReadsEveryTypeExactlyOverManyChunks) {
  testing::TempDir dir;
  const int width = 37, height = 53;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  std::vector<float> floats(n);
  std::vector<half> halves(n);
  std::vector<std::uint32_t> integers(n);
  std::mt19937 random(7);
  for (std::size_t i = 0; i < n; ++i) {
    const bool noisy = i < static_cast<std::size_t>(width) * 16;
    floats[i] = noisy ? std::bit_cast<float>(
                            static_cast<std::uint32_t>(random() & 0x7f7fffffu))  // finite, any bits
                      : static_cast<float>(1e-3 * std::pow(10.0, 9.0 * i / n));
    halves[i].setBits(noisy ? static_cast<std::uint16_t>(random() & 0x7bffu)  // finite
                            : half(static_cast<float>(i % 301) / 7.0f).bits());
    integers[i] = noisy ? static_cast<std::uint32_t>(random()) : static_cast<std::uint32_t>(i % 5);
  }
  const ExrZipChannel channels[] = {channelOf("Y", ExrPixelType::kFloat, floats, width),
                                    channelOf("a_half", ExrPixelType::kHalf, halves, width),
                                    channelOf("count", ExrPixelType::kUint, integers, width)};
  std::vector<std::byte> first;
  for (const unsigned threads : {1u, 3u}) {
    const ThreadBudget budget(threads);
    auto bytes = encodeExrZip(width, height, channels);
    ASSERT_TRUE(bytes) << bytes.error().message;
    if (first.empty()) first = *bytes;
    EXPECT_EQ(*bytes, first) << "the bytes do not depend on the threads";
    ASSERT_TRUE(writeFileAtomic(dir / "z.exr", *bytes));
    EXPECT_EQ(readChannel<float>(dir / "z.exr", "Y", Imf::FLOAT, width, height), floats);
    const auto read_halves = readChannel<half>(dir / "z.exr", "a_half", Imf::HALF, width, height);
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(read_halves[i].bits(), halves[i].bits()) << i;
    EXPECT_EQ(readChannel<std::uint32_t>(dir / "z.exr", "count", Imf::UINT, width, height),
              integers);
  }
  // The noisy first chunk is stored as it is, the smooth ones compressed. The line-offset table
  // (4 chunks) sits right before the first chunk, whose offset it starts with.
  const int chunks = 4;
  const std::size_t raw_chunk_bytes = static_cast<std::size_t>(width) * (4 + 2 + 4) * 16;
  const auto at = [&](std::size_t position, auto value) {
    std::memcpy(&value, first.data() + position, sizeof value);
    return value;
  };
  std::size_t table = 0;
  while (at(table, std::uint64_t{}) != table + 8 * chunks) ++table;
  std::size_t chunk = table + 8 * chunks;
  for (int i = 0; i < chunks; ++i) {
    EXPECT_EQ(at(table + 8 * i, std::uint64_t{}), chunk);
    EXPECT_EQ(at(chunk, std::int32_t{}), 16 * i);  // its first line
    const auto size = static_cast<std::size_t>(at(chunk + 4, std::int32_t{}));
    if (i == 0) {
      EXPECT_EQ(size, raw_chunk_bytes);
    } else {
      EXPECT_LT(size, raw_chunk_bytes * 3 / 5) << "chunk " << i;
    }
    chunk += 8 + size;
  }
  EXPECT_EQ(chunk, first.size());
}

// One column, one row: the smallest images.
TEST(ExrZip, OneColumnAndOneRowImages) {
  testing::TempDir dir;
  for (const auto& [width, height] : {std::pair(1, 40), std::pair(40, 1)}) {
    std::vector<float> values(static_cast<std::size_t>(width) * height);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(i) - 3.5f;
    const ExrZipChannel channel = channelOf("Y", ExrPixelType::kFloat, values, width);
    auto bytes = encodeExrZip(width, height, std::span(&channel, 1));
    ASSERT_TRUE(bytes) << bytes.error().message;
    ASSERT_TRUE(writeFileAtomic(dir / "z.exr", *bytes));
    EXPECT_EQ(readChannel<float>(dir / "z.exr", "Y", Imf::FLOAT, width, height), values);
  }
}

// What no EXR can hold is refused with a reason, never written.
TEST(ExrZip, RefusesWhatNoExrCanHold) {
  const std::vector<float> values(4, 1.0f);
  const auto refused = [&](int width, int height, std::vector<ExrZipChannel> channels,
                           const char* reason) {
    const auto bytes = encodeExrZip(width, height, channels);
    ASSERT_FALSE(bytes) << reason;
    EXPECT_NE(bytes.error().message.find(reason), std::string::npos) << bytes.error().message;
  };
  const ExrZipChannel y = channelOf("Y", ExrPixelType::kFloat, values, 2);
  refused(0, 2, {y}, "no pixels");
  refused(2, 2, {}, "no channel");
  refused(2, 2, {y, y}, "share a name");
  refused(2, 2, {channelOf("", ExrPixelType::kFloat, values, 2)}, "unusable");
  refused(2, 2, {channelOf(std::string(32, 'n'), ExrPixelType::kFloat, values, 2)}, "unusable");
  refused(2, 2, {{"Y", ExrPixelType::kFloat, {}}}, "unusable");
}

}  // namespace
}  // namespace glarecam
