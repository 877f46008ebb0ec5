// What every libFuzzer target of tests/fuzz/ shares (docs/fuzzing.md).
//
// Most of glarecam's parsers read files, not buffers, because their errors name the file and
// because the formats they read (PNG, TIFF, TOML, CSV) are read through file APIs. A target
// writes its input to a file in a directory of its own process and calls the reader there, so
// the fuzzer drives exactly the code a user's file reaches.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace glarecam::fuzz {

// This process's scratch directory (under $TMPDIR or /tmp), made on first use and removed at
// exit. libFuzzer's -fork/-jobs workers are processes, each with its own.
const std::filesystem::path& scratchDirectory();

// Writes the input to `name` inside the scratch directory (replacing what was there) and returns
// its path. Aborts if it cannot: a target that silently tests nothing would be worse.
std::filesystem::path writeScratchFile(const std::filesystem::path& name, const std::uint8_t* data,
                                       std::size_t size);

// The input as text (a JSON or TOML parser sees these bytes, invalid UTF-8 included).
inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Logging off: the readers warn through spdlog, and a fuzzer's run prints millions of inputs.
void silenceLogging();

}  // namespace glarecam::fuzz
