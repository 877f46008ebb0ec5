// libFuzzer target: a stack's result document (glarecam.result/1, docs/process.md) as glarecamd
// reads result.json files back from disk (the day's products, the status page after a restart):
// the one reader, then what is read turned into a sweep row and written back, which must read
// again as the same result.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/json.h"
#include "pipeline/result.h"
#include "pipeline/sweep_table.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto document = glarecam::parseJsonText(glarecam::fuzz::asText(data, size), "result.json");
  if (!document) return 0;
  const auto result = glarecam::pipeline::resultFromJson(*document, "result.json");
  if (!result) return 0;
  (void)glarecam::pipeline::sweepRowFromResult(*result, "stack");
  const auto again = glarecam::pipeline::resultFromJson(
      *glarecam::parseJsonText(glarecam::jsonText(glarecam::pipeline::toJson(*result)), "again"),
      "again");
  if (!again || !(*again == *result)) std::abort();  // what the writer writes, the reader reads
  return 0;
}
