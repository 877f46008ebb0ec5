#include "support/test_support.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <sstream>

namespace glarecam::testing {
namespace fs = std::filesystem;

TempDir::TempDir() {
  std::string pattern = (fs::temp_directory_path() / "glarecam-test-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

fs::path testDataDir() { return GLARECAM_TEST_DATA_DIR; }

capture::SimulationOptions smallScene(double alpha_deg, int width, int height) {
  capture::SimulationOptions options;
  options.alpha_deg = alpha_deg;
  options.width = width;
  options.height = height;
  // A narrow field of view keeps the lobe many pixels wide on a small frame.
  options.horizontal_fov_deg = 16.0;
  return options;
}

capture::SimulatedStack writeSmallStack(const fs::path& directory,
                                        const capture::SimulationOptions& options) {
  auto stack = capture::simulateStack(options);
  EXPECT_TRUE(stack.has_value()) << (stack ? "" : stack.error().message);
  if (!stack) return {};
  auto status = capture::writeSimulatedStack(directory, *stack);
  EXPECT_TRUE(status.has_value()) << (status ? "" : status.error().message);
  return std::move(*stack);
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

}  // namespace glarecam::testing
