// `glarecam process`: one recorded stack -> calibrated luminance image and result.
// Reads the stack (stack_io.h), merges it (hdr_merge.h), summarises it, and writes into the
// output directory (default STACK/result/): luminance.exr (float cd/m², channel Y),
// quality.exr (relative uncertainty, valid frame count, bound flags), luminance.png (false
// colour) and result.json (glarecam.result/1), each file atomically, result.json last.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/error.h"

namespace glarecam::pipeline {

struct ProcessOptions {
  std::optional<std::filesystem::path> calibration_file;  // overrides the stack's calibration
  std::optional<std::filesystem::path> output_directory;  // default: STACK/result
  unsigned threads = 0;                                   // 0: all cores
  bool show_progress = true;
};

struct ProcessSummary {
  std::filesystem::path output_directory;
  nlohmann::json result;
  std::string briefReport() const;  // one line for logs
};

Result<ProcessSummary> processStack(const std::filesystem::path& stack_directory,
                                    const ProcessOptions& options = {});

}  // namespace glarecam::pipeline
