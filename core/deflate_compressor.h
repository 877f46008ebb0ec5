// A libdeflate compressor, owned: the one used by every encoder of core (PNG, EXR ZIP).
// Internal to core (libdeflate is a private dependency).
#pragma once

#include <libdeflate.h>

#include <memory>

namespace glarecam {

struct DeflateCompressorFree {
  void operator()(libdeflate_compressor* compressor) const {
    libdeflate_free_compressor(compressor);
  }
};
using DeflateCompressor = std::unique_ptr<libdeflate_compressor, DeflateCompressorFree>;

// A compressor at `level` (1 fastest … 12 smallest), or null when out of memory.
inline DeflateCompressor makeDeflateCompressor(int level) {
  return DeflateCompressor(libdeflate_alloc_compressor(level));
}

}  // namespace glarecam
