// An output tree's entries as glarecam writes them, for the tests of what reads or deletes them
// (retention, retention's scheduling, what a restart recalls): a stack with its manifest and
// frame data of a given size, a result with its result.json, and a day's sweep table.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "core/json.h"
#include "daemon/storage/output_tree.h"
#include "pipeline/process_stack.h"  // kResultFileName
#include "pipeline/result.h"
#include "support/test_support.h"
#include "tests/pipeline/result_fixture.h"

namespace glarecam::testing {

// A stack as glarecam writes it (its manifest, glarecam.stack/1) with `bytes` of frame data.
inline void makeGlarecamStack(const std::filesystem::path& directory, std::uint64_t bytes = 1000) {
  std::filesystem::create_directories(directory);
  writeText(directory / "stack.json", R"({"schema": "glarecam.stack/1"})");
  writeText(directory / "frame-0.png", std::string(bytes, 'x'));
}

// A complete result: result.json as `process` writes it (tests/pipeline/result_fixture.h) with
// Lmax `lmax_cd_m2`, the stack's id (the directory's name) and α, and the images it names
// (luminance.exr, quality.exr, luminance.png) of `image_bytes` each.
inline void makeGlarecamResult(const std::filesystem::path& directory, double lmax_cd_m2 = 1000,
                               std::optional<double> alpha_deg = std::nullopt,
                               std::uint64_t image_bytes = 500) {
  std::filesystem::create_directories(directory);
  pipeline::StackResult result = minimalResult(lmax_cd_m2, alpha_deg);
  result.stack = directory.filename().string();
  writeText(directory / pipeline::kResultFileName, jsonText(pipeline::toJson(result)));
  for (const std::string& image : result.outputs.files())
    writeText(directory / image, std::string(image_bytes, 'y'));
}

// A processed stack of `id`: the stack and its complete result.
inline void makeProcessed(const daemon::OutputTree& tree, const std::string& id,
                          std::uint64_t bytes = 1000) {
  makeGlarecamStack(tree.stacks() / id, bytes);
  makeGlarecamResult(tree.results() / id);
}

}  // namespace glarecam::testing
