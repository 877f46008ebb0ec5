#include "support/test_support.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <png.h>
#include <stdlib.h>
#include <sys/socket.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "core/stack_io.h"

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

UniqueFd connectLoopback(int port) {
  UniqueFd fd(socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(connect(fd.get(), reinterpret_cast<sockaddr*>(&address), sizeof address), 0)
      << "127.0.0.1:" << port << ": " << std::strerror(errno);
  return fd;
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

TestStack writeTestStack(const fs::path& directory, double alpha_deg) {
  constexpr int kWidth = 160, kHeight = 128;
  constexpr double kBlackDn = 64, kSaturationDn = 4000;
  TestStack stack;
  Calibration calibration;
  calibration.black_level_dn = kBlackDn;
  calibration.saturation_dn = kSaturationDn;
  calibration.luminance_factor = 2.5;
  calibration.reference_f_number = 8.0;
  calibration.intrinsics = {.fx = 500, .fy = 500, .cx = kWidth / 2.0, .cy = kHeight / 2.0};
  calibration.noise = NoiseModel{.read_noise_dn = 2, .dn_per_electron = 0.5};
  stack.manifest.id = "test-stack";
  stack.manifest.alpha_deg = alpha_deg;
  stack.manifest.calibration = calibration;
  std::mt19937 random(17);
  std::uniform_int_distribution<int> level(static_cast<int>(kBlackDn),
                                           static_cast<int>(kSaturationDn));
  for (int i = 0; i < 4; ++i) {
    RawFrame frame(kWidth, kHeight);
    for (std::size_t p = 0; p < frame.pixelCount(); ++p)
      frame.data()[p] = static_cast<std::uint16_t>(level(random));
    stack.frames.push_back(std::move(frame));
    stack.manifest.frames.push_back({.file = "frame-0" + std::to_string(i) + ".png",
                                     .exposure_us = 20.0 * std::pow(10.0, i),
                                     .gain_db = 0.0,
                                     .f_number = 8.0,
                                     .nd_transmission = 1.0});
  }
  fs::create_directories(directory.parent_path());
  StackWriteRequest request;
  request.manifest = stack.manifest;
  request.frames = stack.frames;
  request.text_files.emplace_back("truth.json", R"({"schema": "glarecam.truth/1"})");
  const Status written = writeStack(directory, request);
  EXPECT_TRUE(written.has_value()) << (written ? "" : written.error().message);
  return stack;
}

int pdfPageCount(const std::filesystem::path& pdf) {
  const std::string text = readText(pdf);
  std::smatch match;
  if (!std::regex_search(text, match,
                         std::regex(R"(/Type /Pages\s*/Kids \[[^\]]*\]\s*/Count (\d+))")))
    return -1;
  return std::stoi(match[1]);
}

bool noTemporaryFiles(const std::filesystem::path& directory) {
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    if (entry.path().filename().string().rfind(".tmp-", 0) == 0) return false;
  return true;
}

RgbPicture readPngRgb(const std::filesystem::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  RgbPicture picture;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    ADD_FAILURE() << path << ": " << image.message;
    return picture;
  }
  image.format = PNG_FORMAT_RGB;
  picture.width = static_cast<int>(image.width);
  picture.height = static_cast<int>(image.height);
  picture.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, picture.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << path << ": " << image.message;
    picture = {};
  }
  return picture;
}

}  // namespace glarecam::testing
