// An OpenEXR file with ZIP compression, encoded here through libdeflate (docs/process.md,
// "Output encodings"): OpenEXR 3.1's own ZIP runs zlib at its default level, 3-4 times slower
// for the same size. The file is OpenEXR's scan-line layout (openexr.com, "OpenEXR File Layout"):
// magic and version, the required header attributes, the line-offset table, then one chunk per
// 16 scan lines. Each chunk holds its lines channel by channel (channels sorted by name, values
// little-endian), its bytes split into even and odd halves and delta-coded (OpenEXR's predictor),
// then zlib-compressed; a chunk that would not shrink is stored as it is, as OpenEXR does.
// Every EXR reader (OpenEXR, OpenCV, Blender, Nuke) reads it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"

namespace glarecam {

// OpenEXR's pixel types, as their numbers in the file.
enum class ExrPixelType : std::int32_t { kUint = 0, kHalf = 1, kFloat = 2 };

inline constexpr int exrPixelBytes(ExrPixelType type) {
  return type == ExrPixelType::kHalf ? 2 : 4;
}

// One channel: its rows, each written by `row(y, out)` as width values of `type`, little-endian
// (the encoder asks for each row once, from any of its threads; converting a row as it is asked
// for spares a whole converted copy of the image).
struct ExrZipChannel {
  std::string name;  // at most 31 bytes (EXR without the long-names flag)
  ExrPixelType type = ExrPixelType::kFloat;
  std::function<void(int y, std::byte* out)> row;
};

// libdeflate level 1: measured on a 5 MP luminance and quality image (docs/process.md), higher
// levels cost up to 2.5x the time for 1-2 % smaller files.
inline constexpr int kExrDeflateLevel = 1;

// The file's bytes. Chunks compress on up to availableThreads() threads (core/parallel.h).
// Channels must be named, distinct and have rows; width and height at least 1.
Result<std::vector<std::byte>> encodeExrZip(int width, int height,
                                            std::span<const ExrZipChannel> channels,
                                            int deflate_level = kExrDeflateLevel);

}  // namespace glarecam
