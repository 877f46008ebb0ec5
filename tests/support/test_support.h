// Shared test helpers any layer's tests may use (they need core only): temporary directories,
// the committed test data, text files in one line, and a small stack written by core's own
// writer. The simulator's helpers (scenes, simulated stacks) are in support/sim_support.h.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/stack_manifest.h"
#include "core/unique_fd.h"

namespace glarecam::testing {

// A fresh directory under the system temp dir, removed with everything in it at destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

std::filesystem::path testDataDir();

// Pure trigonometry in doubles: agreement to 1e-9° is rounding, not approximation.
inline constexpr double kExactDeg = 1e-9;

std::string readText(const std::filesystem::path& path);
// A TCP connection to 127.0.0.1:`port`, for tests that drive a server byte by byte.
UniqueFd connectLoopback(int port);
void writeText(const std::filesystem::path& path, const std::string& text);

// What writeTestStack() wrote: the manifest and the frames, to compare a read against.
struct TestStack {
  StackManifest manifest;
  std::vector<RawFrame> frames;
};

// Writes a small stack with core's writer (core/stack_io.h; creating its parent directories) and
// fails the calling test on error: 160x128 frames of pseudo-random 12-bit values at decade
// exposures, 16-bit PNG, an inline calibration (reference f-number 8, the frames at f/8), α 40°
// unless given, and a text file truth.json, as a simulated stack carries.
TestStack writeTestStack(const std::filesystem::path& directory, double alpha_deg = 40.0);

// The page count in a PDF's page tree ("/Type /Pages … /Count N", as Cairo writes it); -1 when
// the file has none.
int pdfPageCount(const std::filesystem::path& pdf);
// Whether a directory holds no temporary file of an atomic write (core/atomic_file.h: ".tmp-…").
bool noTemporaryFiles(const std::filesystem::path& directory);

// A drawn page read back as 8-bit RGB (the pictures' tests).
using RgbPixel = std::array<std::uint8_t, 3>;
struct RgbPicture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes a pixel
  RgbPixel at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};
// A PNG file as RGB; empty, with a failure added to the calling test, when it cannot be read.
RgbPicture readPngRgb(const std::filesystem::path& path);

}  // namespace glarecam::testing
