// Shared test helpers: temporary directories, small simulated stacks in one line, and
// access to the committed test data.
#pragma once

#include <filesystem>
#include <string>

#include "capture/sim/simulated_stack.h"
#include "core/error.h"

namespace glarecam::testing {

// A fresh directory under the system temp dir, removed with everything in it at destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

std::filesystem::path testDataDir();

// Simulator options for a small, fast scene (the default sizes are for real use).
capture::SimulationOptions smallScene(double alpha_deg = 40.0, int width = 160, int height = 128);

// Simulates and writes a stack; fails the calling test on error.
capture::SimulatedStack writeSmallStack(const std::filesystem::path& directory,
                                        const capture::SimulationOptions& options = smallScene());

std::string readText(const std::filesystem::path& path);
void writeText(const std::filesystem::path& path, const std::string& text);

}  // namespace glarecam::testing
