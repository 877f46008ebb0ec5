// libFuzzer target: a goniophotometer file (pab-opto/Radiance or Zemax BSDF text, docs/brdf.md),
// read as `glarecam brdf` reads it, and when it parses, its sampling checked, its noise
// estimated and (for small measurements) its luminance picture drawn at the smallest size, so
// that whatever angles and values the readers let through meet the triangulation and the
// interpolation.
#include <cstddef>
#include <cstdint>

#include "brdf/brdf_file.h"
#include "brdf/brdf_luminance.h"
#include "tests/fuzz/fuzz_support.h"

namespace {
// The picture costs about a millisecond per hundred samples at 65 px: bounded, so one input
// costs milliseconds.
constexpr std::size_t kMaxDrawnSamples = 2000;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glarecam::brdf;
  const auto measurements = parseBrdfText(glarecam::fuzz::asText(data, size), "fuzz.dat");
  if (!measurements) return 0;
  for (const BrdfMeasurement& m : *measurements) {
    (void)estimateRelativeNoise(m);
    const auto sampling = checkSampling(m);
    if (!sampling || m.samples.size() > kMaxDrawnSamples) continue;
    LuminanceImageOptions options;
    options.max_size_px = 65;
    (void)luminanceUnderSun(m, *sampling, options);
  }
  return 0;
}
