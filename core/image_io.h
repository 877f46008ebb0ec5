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
#include <variant>
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

// A frame's size from its header alone (PNG's IHDR, TIFF's first directory), without decoding:
// for planning memory before reading whole stacks.
struct FrameSize {
  int width = 0, height = 0;
};
Result<FrameSize> readFrameSize(const std::filesystem::path& path);

// How glarecam writes PNGs, frames and pictures alike: no row filter, one IDAT chunk deflated by
// libdeflate at level 1. Measured on a simulated 5 MP stack (docs/process.md, "Output
// encodings"): the false-colour picture takes 48 ms for 3.85 MB, against 119 ms for 4.47 MB with
// zlib at level 1 (libpng's encoder) and 60 ms for 5.22 MB with the Sub filter. Filters predict
// smooth images; raw frames and their false colour are noisy at the pixel scale.
inline constexpr int kPngDeflateLevel = 1;

// Encodes a raw frame as a single-channel 16-bit PNG (for bit_depth 16) or 8-bit PNG.
Result<std::vector<std::byte>> encodePngGray(const RawFrame& frame, int bit_depth = 16,
                                             int deflate_level = kPngDeflateLevel);
Status writePngGray(const std::filesystem::path& path, const RawFrame& frame, int bit_depth = 16);

// 16-bit single-channel TIFF in strips (for tests and tools that produce TIFF stacks), with
// libtiff's Deflate (libdeflate in Debian) or zstd at their fastest levels, or uncompressed.
enum class TiffCompression { kNone, kDeflate, kZstd };
Status writeTiffGray16(const std::filesystem::path& path, const RawFrame& frame,
                       TiffCompression compression = TiffCompression::kNone);

// rgb holds width*height*3 bytes, row-major.
Status writePngRgb(const std::filesystem::path& path, int width, int height,
                   std::span<const std::uint8_t> rgb, int deflate_level = kPngDeflateLevel);

// How a channel is stored in an EXR (every reader converts each to float):
//   kFloat    32-bit float, exact;
//   kFloat24  32-bit float rounded to 16 significant bits (the low 8 of the mantissa zero): within
//             a relative 2^-16 = 1.5e-5, NaN and infinities kept. Noisy float32 barely compresses
//             because its low bits are noise; without them PIZ halves it (PXR24's rounding, but
//             PIZ is 6 times faster than PXR24's zlib; docs/process.md, "Output encodings");
//   kHalf   16-bit float: relative precision 2^-11 (4.9e-4), magnitudes up to 65504 (larger
//           become infinite: never for absolute luminance, whose glare peaks reach 1e9 cd/m²);
//   kUint   32-bit unsigned integer, for counts and flags (values rounded; NaN and negatives
//           stored as 0, values beyond 2^32 − 1 as 2^32 − 1).
enum class ExrStorage { kFloat, kFloat24, kHalf, kUint };

// One compression per file, both lossless: kZip (deflate, encoded through libdeflate by
// core/exr_zip.h) and kPiz (OpenEXR's wavelet and Huffman: small for HALF and kFloat24 channels,
// slow on unrounded noisy float32; measured in docs/process.md, "Output encodings").
enum class ExrCompression { kZip, kPiz };

// An image of named channels, written atomically. A channel's pixels are float, or bytes (counts
// and flags, stored without a float copy).
struct ExrChannel {
  std::string name;
  std::variant<const FloatImage*, const ByteImage*> image;
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
