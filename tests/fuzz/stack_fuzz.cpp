// libFuzzer target: a stack's manifest (stack.json), read by readStack() as `glarecam process`
// reads a stack. The input is stack.json; the directory also holds two valid 32×24 frames named
// as the seeds name them (frame-00.png, frame-01.png), so the fuzzer reaches past the manifest
// into frame lookup, path checks, calibration and frame decoding. Frames' own bytes are
// frame_fuzz's job.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/image_io.h"
#include "core/stack_io.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

const std::filesystem::path& stackDirectory() {
  static const std::filesystem::path directory = [] {
    std::filesystem::path dir = glarecam::fuzz::scratchDirectory() / "stack";
    std::filesystem::create_directories(dir);
    glarecam::RawFrame frame(32, 24);
    for (int y = 0; y < frame.height(); ++y)
      for (int x = 0; x < frame.width(); ++x)
        frame.at(x, y) = static_cast<std::uint16_t>(64 + 97 * x + 13 * y);  // black 64 .. < 4000
    for (const char* name : {"frame-00.png", "frame-01.png"})
      if (!glarecam::writePngGray(dir / name, frame)) std::abort();
    return dir;
  }();
  return directory;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  stackDirectory();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  glarecam::fuzz::writeScratchFile("stack/stack.json", data, size);
  glarecam::StackReadOptions options;
  options.threads = 1;
  (void)glarecam::readStack(stackDirectory(), options);
  options.decode_frames = false;
  options.require_calibration = false;
  (void)glarecam::readStack(stackDirectory(), options);
  return 0;
}
