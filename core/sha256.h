// SHA-256 (FIPS 180-4) of bytes and of files, as lowercase hex: the identity a result records for
// the calibration file it rests on, so that a later reader can tell whether it is the same file.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/error.h"

namespace glarecam {

// Incremental SHA-256: update() with the bytes in any pieces, then hexDigest() once.
class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  // The digest of everything updated so far, as 64 lowercase hex digits; ends the hashing.
  std::string hexDigest();

 private:
  void compress(const std::uint8_t* block);

  std::array<std::uint32_t, 8> state_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_bytes_ = 0;
};

std::string sha256Hex(std::string_view bytes);

// The SHA-256 of a file's contents; kBadInput naming the file when it cannot be read.
Result<std::string> sha256OfFile(const std::filesystem::path& path);

}  // namespace glarecam
