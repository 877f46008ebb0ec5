// Reading and writing the image files of a stack and its results.
// - Raw frames: single-channel 8- or 16-bit PNG or TIFF (strips), values returned unchanged
//   in a 16-bit container (8-bit frames are widened, not scaled).
// - Float images: OpenEXR, one FLOAT channel ("Y" for luminance, as EXR viewers expect).
// - Pictures: 8-bit RGB PNG for false-colour renderings.
// Every decoder is defensive: a truncated, colour, oversize or otherwise unusable file yields
// an Error naming the file and the problem, never a crash. Writers are atomic (atomic_file.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"

namespace glarecam {

struct DecodedFrame {
  RawFrame pixels;
  int bit_depth = 16;  // of the file: 8 or 16
};

// Largest frame accepted (pixels), far above any machine-vision sensor: protects against
// headers that announce absurd sizes.
inline constexpr std::uint64_t kMaxFramePixels = 1ull << 27;
// No PNG (deflate, at most ~1032:1) or TIFF (LZW, at most ~4096:1) holds more pixel bytes than
// this many times its file size: a header promising more is a lie, refused before allocating.
inline constexpr std::uint64_t kMaxCompressionRatio = 4096;

Result<DecodedFrame> readRawFrame(const std::filesystem::path& path);

// Encodes a raw frame as a single-channel 16-bit PNG (for bit_depth 16) or 8-bit PNG.
Result<std::vector<std::byte>> encodePngGray(const RawFrame& frame, int bit_depth = 16,
                                             int zlib_level = 3);
Status writePngGray(const std::filesystem::path& path, const RawFrame& frame, int bit_depth = 16);

// 16-bit single-channel TIFF (for tests and tools that produce TIFF stacks).
Status writeTiffGray16(const std::filesystem::path& path, const RawFrame& frame);

// rgb holds width*height*3 bytes, row-major.
Status writePngRgb(const std::filesystem::path& path, int width, int height,
                   std::span<const std::uint8_t> rgb, int zlib_level = 3);

// How a channel is stored in an EXR (every reader converts each to float):
//   kFloat  32-bit float (lossless but for kPxr24 compression, which keeps 15 mantissa bits);
//   kHalf   16-bit float: relative precision 2^-11 (4.9e-4), magnitudes up to 65504 (larger
//           become infinite: never for absolute luminance, whose glare peaks reach 1e9 cd/m²);
//   kUint   32-bit unsigned integer, for counts and flags (values rounded; NaN and negatives
//           stored as 0, values beyond 2^32 − 1 as 2^32 − 1).
enum class ExrStorage { kFloat, kHalf, kUint };

// One compression per file (OpenEXR's): kZip (lossless, zlib), kPiz (lossless wavelet: fast,
// best for HALF and integer channels), kPxr24 (FLOAT channels rounded to 24 bits, i.e. to a
// relative 2^-16 = 1.5e-5, then zlib: noisy float32 compresses about twice as well as with kZip;
// HALF and UINT channels stay lossless).
enum class ExrCompression { kZip, kPiz, kPxr24 };

// An image of named channels, written atomically.
struct ExrChannel {
  std::string name;
  const FloatImage* image = nullptr;
  ExrStorage storage = ExrStorage::kFloat;
};
Status writeExr(const std::filesystem::path& path, std::span<const ExrChannel> channels,
                ExrCompression compression = ExrCompression::kZip);
Status writeExr(const std::filesystem::path& path, const FloatImage& image,
                const std::string& channel = "Y",
                ExrCompression compression = ExrCompression::kZip);

// Reads channel `channel` (or, when it is absent, the only channel) of an EXR as float.
Result<FloatImage> readExr(const std::filesystem::path& path, const std::string& channel = "Y");

}  // namespace glarecam
