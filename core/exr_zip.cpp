#include "core/exr_zip.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>

#include "core/deflate_compressor.h"
#include "core/parallel.h"

namespace glarecam {
namespace {

static_assert(std::endian::native == std::endian::little,
              "EXR values are little-endian: the encoder copies them as they are in memory");

constexpr std::uint32_t kExrMagic = 20000630;
constexpr std::uint32_t kExrVersion = 2;  // single-part scan-line file, short names
constexpr std::uint8_t kZipCompression = 3;
constexpr std::uint8_t kIncreasingY = 0;
constexpr int kZipLinesPerChunk = 16;  // OpenEXR's ZIP_COMPRESSION (ZIPS is 1)
constexpr std::size_t kMaxNameBytes = 31;

class ExrHeaderWriter {
 public:
  explicit ExrHeaderWriter(std::vector<std::byte>& out) : out_(out) {}
  template <typename T>
  void put(T value) {
    const auto bytes = std::bit_cast<std::array<std::byte, sizeof(T)>>(value);
    out_.insert(out_.end(), bytes.begin(), bytes.end());
  }
  void text(const std::string& s) {
    for (const char c : s) out_.push_back(static_cast<std::byte>(c));
    out_.push_back(std::byte{0});
  }
  void attribute(const std::string& name, const std::string& type, std::int32_t size) {
    text(name);
    text(type);
    put(size);
  }

 private:
  std::vector<std::byte>& out_;
};

// One chunk's bytes as OpenEXR's ZIP predictor leaves them: the even bytes then the odd ones,
// each the difference to the one before it, plus 128 (modulo 256).
void exrZipPredict(const std::uint8_t* raw, std::size_t size, std::uint8_t* out) {
  std::uint8_t* even = out;
  std::uint8_t* odd = out + (size + 1) / 2;
  for (std::size_t i = 0; i + 1 < size; i += 2) {
    *even++ = raw[i];
    *odd++ = raw[i + 1];
  }
  if (size % 2 != 0) *even = raw[size - 1];
  std::uint8_t previous = out[0];
  for (std::size_t i = 1; i < size; ++i) {
    const std::uint8_t current = out[i];
    out[i] = static_cast<std::uint8_t>(current - previous + 128);
    previous = current;
  }
}

}  // namespace

Result<std::vector<std::byte>> encodeExrZip(int width, int height,
                                            std::span<const ExrZipChannel> channels,
                                            int deflate_level) {
  if (width < 1 || height < 1) return fail(ErrorCode::kInternal, "EXR image has no pixels");
  if (channels.empty()) return fail(ErrorCode::kInternal, "EXR image has no channel");
  std::vector<const ExrZipChannel*> sorted;
  for (const ExrZipChannel& channel : channels) {
    if (channel.name.empty() || channel.name.size() > kMaxNameBytes || !channel.row)
      return fail(ErrorCode::kInternal, "EXR channel '" + channel.name + "' is unusable");
    sorted.push_back(&channel);
  }
  std::ranges::sort(sorted, {}, &ExrZipChannel::name);
  if (std::ranges::adjacent_find(sorted, {}, &ExrZipChannel::name) != sorted.end())
    return fail(ErrorCode::kInternal, "two EXR channels share a name");

  const auto columns = static_cast<std::size_t>(width);
  std::size_t line_bytes = 0;
  for (const ExrZipChannel* channel : sorted) line_bytes += columns * exrPixelBytes(channel->type);
  const int chunks = (height + kZipLinesPerChunk - 1) / kZipLinesPerChunk;
  const std::size_t chunk_bytes = line_bytes * kZipLinesPerChunk;

  // Each chunk compressed on its own (OpenEXR reads them independently), its stored bytes kept.
  std::vector<std::vector<std::uint8_t>> stored(static_cast<std::size_t>(chunks));
  std::atomic<bool> out_of_memory{false};
  parallelRows(chunks, availableThreads(), [&](int first, int end) {
    const DeflateCompressor compressor = makeDeflateCompressor(deflate_level);
    if (!compressor) {
      out_of_memory = true;
      return;
    }
    const std::size_t bound = libdeflate_zlib_compress_bound(compressor.get(), chunk_bytes);
    std::vector<std::uint8_t> raw(chunk_bytes), predicted(chunk_bytes), compressed(bound);
    for (int chunk = first; chunk < end; ++chunk) {
      const int y0 = chunk * kZipLinesPerChunk;
      const int lines = std::min(kZipLinesPerChunk, height - y0);
      std::uint8_t* at = raw.data();
      for (int y = y0; y < y0 + lines; ++y) {
        for (const ExrZipChannel* channel : sorted) {
          channel->row(y, reinterpret_cast<std::byte*>(at));
          at += columns * exrPixelBytes(channel->type);
        }
      }
      const auto size = static_cast<std::size_t>(at - raw.data());
      exrZipPredict(raw.data(), size, predicted.data());
      const std::size_t packed = libdeflate_zlib_compress(compressor.get(), predicted.data(), size,
                                                          compressed.data(), bound);
      const bool shrinks = packed != 0 && packed < size;  // otherwise stored as it is
      const std::uint8_t* bytes = shrinks ? compressed.data() : raw.data();
      stored[static_cast<std::size_t>(chunk)].assign(bytes, bytes + (shrinks ? packed : size));
    }
  });
  if (out_of_memory) return fail(ErrorCode::kInternal, "out of memory encoding EXR");

  std::vector<std::byte> file;
  ExrHeaderWriter w(file);
  w.put(kExrMagic);
  w.put(kExrVersion);
  std::int32_t channel_list_bytes = 1;
  for (const ExrZipChannel* channel : sorted)
    channel_list_bytes += static_cast<std::int32_t>(channel->name.size() + 1 + 16);
  w.attribute("channels", "chlist", channel_list_bytes);
  for (const ExrZipChannel* channel : sorted) {
    w.text(channel->name);
    w.put(static_cast<std::int32_t>(channel->type));
    w.put(std::uint32_t{0});  // pLinear 0 and three reserved bytes
    w.put(std::int32_t{1});   // x sampling
    w.put(std::int32_t{1});   // y sampling
  }
  w.put(std::uint8_t{0});
  w.attribute("compression", "compression", 1);
  w.put(kZipCompression);
  for (const char* window : {"dataWindow", "displayWindow"}) {
    w.attribute(window, "box2i", 16);
    for (const std::int32_t v : {0, 0, width - 1, height - 1}) w.put(v);
  }
  w.attribute("lineOrder", "lineOrder", 1);
  w.put(kIncreasingY);
  w.attribute("pixelAspectRatio", "float", 4);
  w.put(1.0f);
  w.attribute("screenWindowCenter", "v2f", 8);
  w.put(0.0f);
  w.put(0.0f);
  w.attribute("screenWindowWidth", "float", 4);
  w.put(1.0f);
  w.put(std::uint8_t{0});  // end of header

  constexpr std::size_t kChunkHeaderBytes = 8;  // its first line and its size, int32 each
  std::uint64_t offset = file.size() + sizeof(std::uint64_t) * stored.size();
  std::size_t total = offset;
  for (const auto& chunk : stored) total += kChunkHeaderBytes + chunk.size();
  file.reserve(total);
  for (const auto& chunk : stored) {
    w.put(offset);
    offset += kChunkHeaderBytes + chunk.size();
  }
  for (std::size_t chunk = 0; chunk < stored.size(); ++chunk) {
    w.put(static_cast<std::int32_t>(chunk * kZipLinesPerChunk));
    w.put(static_cast<std::int32_t>(stored[chunk].size()));
    const auto* bytes = reinterpret_cast<const std::byte*>(stored[chunk].data());
    file.insert(file.end(), bytes, bytes + stored[chunk].size());
  }
  return file;
}

}  // namespace glarecam
