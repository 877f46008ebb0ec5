// glarecamd's output directory ([output] root): stacks/<id>/ as captured, results/<id>/ as
// processed (or results/<id>.failed for a stack that cannot be), days/<YYYY-MM-DD>/ with the day's
// sweep, fits and data sheet. Everything in it is written atomically through hidden staging
// entries (core/atomic_file.h), so what a killed glarecamd leaves behind is only those.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "core/error.h"

namespace glarecam::daemon {

// Beside results/<id>/: the stack could not be processed (its reason inside).
inline constexpr const char* kFailedSuffix = ".failed";

class OutputTree {
 public:
  explicit OutputTree(std::filesystem::path root = {}) : root_(std::move(root)) {}

  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path stacks() const;
  std::filesystem::path results() const;
  std::filesystem::path days() const;

  // Creates stacks/, results/ and days/; the first that cannot be made.
  Status prepare() const;
  // Removes what a killed run left half-written (staging entries) and returns how many; only at
  // start, before anything writes.
  std::size_t removeLeftovers() const;
  // The stacks that have neither a result nor a .failed mark (an earlier run's), by name.
  std::vector<std::filesystem::path> unprocessedStacks() const;
  // Whether a write would stick now: the directories exist and a directory made in stacks/ does
  // (statvfs cannot see every refusal: a remount, a quota, a dying card).
  bool writable() const;

 private:
  std::filesystem::path root_;
};

}  // namespace glarecam::daemon
