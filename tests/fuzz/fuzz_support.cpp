#include "tests/fuzz/fuzz_support.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>

namespace glarecam::fuzz {

namespace {

[[noreturn]] void die(const std::string& message) {
  std::fprintf(stderr, "fuzz target: %s\n", message.c_str());
  std::abort();
}

std::filesystem::path makeScratchDirectory() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/glarecam-fuzz-XXXXXX";
  if (!::mkdtemp(pattern.data())) die("cannot make a scratch directory from " + pattern);
  std::atexit([] {
    std::error_code ignored;
    std::filesystem::remove_all(scratchDirectory(), ignored);
  });
  return pattern;
}

}  // namespace

const std::filesystem::path& scratchDirectory() {
  static const std::filesystem::path directory = makeScratchDirectory();
  return directory;
}

std::filesystem::path writeScratchFile(const std::filesystem::path& name, const std::uint8_t* data,
                                       std::size_t size) {
  std::filesystem::path path = scratchDirectory() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) die("cannot write " + path.string());
  return path;
}

void silenceLogging() { spdlog::set_level(spdlog::level::off); }

}  // namespace glarecam::fuzz
