// libFuzzer target: a sweep table (sweep.csv, docs/datasheet.md), read as `glarecam fit` and
// `glarecam datasheet` read it, and fitted when it parses: the fits meet whatever numbers the
// reader lets through (tiny, huge, repeated α), and the fits' JSON written as glarecam writes it.
// Tables are capped at kMaxFittedRows rows for the fit so that one input costs milliseconds, not
// the fuzzer's whole budget.
#include <cstddef>
#include <cstdint>

#include "core/json.h"
#include "pipeline/glare_fits.h"
#include "pipeline/sweep_table.h"
#include "tests/fuzz/fuzz_support.h"

namespace {
constexpr std::size_t kMaxFittedRows = 24;  // cost is linear in rows; seeds have 16
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = glarecam::fuzz::writeScratchFile("sweep.csv", data, size);
  auto table = glarecam::pipeline::readSweepTable(path);
  if (!table || table->rows.size() > kMaxFittedRows) return 0;
  glarecam::pipeline::sortByAlpha(*table);
  const auto fits = glarecam::pipeline::fitSweep(*table);
  // As `glarecam fit --json` and the day sheets write it: a CSV cell's invalid UTF-8 (a suspect
  // note, a stack name) reaches the warnings, and jsonText() replaces it (plain dump() throws).
  if (fits) (void)glarecam::jsonText(glarecam::pipeline::fitsJson(*fits));
  return 0;
}
