// libFuzzer target: a raw frame file (PNG or TIFF, told apart by its signature), read as a
// stack's frames are read: readFrameSize() (the header only, for memory planning) and
// readRawFrame() (the whole decode through libpng/libtiff and glarecam's own checks).
#include <cstddef>
#include <cstdint>

#include "core/image_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = glarecam::fuzz::writeScratchFile("frame", data, size);
  const auto header = glarecam::readFrameSize(path);
  const auto frame = glarecam::readRawFrame(path);
  // The header's size is the decoded frame's: the planner must not under-reserve.
  if (header && frame &&
      (header->width != frame->pixels.width() || header->height != frame->pixels.height()))
    __builtin_trap();
  return 0;
}
