#include "daemon/storage/output_tree.h"

#include <stdlib.h>

#include <algorithm>
#include <string>

#include "core/atomic_file.h"
#include "daemon/storage/day_products.h"
#include "pipeline/process_stack.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

fs::path OutputTree::stacks() const { return root_ / kStacksDirectory; }
fs::path OutputTree::results() const { return root_ / kResultsDirectory; }
fs::path OutputTree::days() const { return root_ / kDaysDirectory; }

Status OutputTree::prepare() const {
  for (const fs::path& directory : {stacks(), results(), days()})
    GLARECAM_CHECK(ensureDirectory(directory));
  return {};
}

std::size_t OutputTree::removeLeftovers() const {
  std::size_t removed = removeStaleTemporaries(stacks());
  std::error_code error;
  for (const fs::path& directory : {results(), days()}) {
    removed += removeStaleTemporaries(directory);
    for (const auto& entry : fs::directory_iterator(directory, error))
      if (entry.is_directory(error)) removed += removeStaleTemporaries(entry.path());
  }
  return removed;
}

std::vector<fs::path> OutputTree::unprocessedStacks() const {
  std::error_code error;
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(stacks(), error)) {
    const std::string id = entry.path().filename().string();
    if (entry.is_directory(error) && fs::exists(entry.path() / "stack.json", error) &&
        !fs::exists(results() / id / pipeline::kResultFileName, error) &&
        !fs::exists(results() / (id + kFailedSuffix), error))
      found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

bool OutputTree::writable() const {
  if (!prepare()) return false;
  std::string probe = (stacks() / (std::string(kTemporaryPrefix) + "probe-XXXXXX")).string();
  if (!mkdtemp(probe.data())) return false;
  std::error_code error;
  fs::remove(probe, error);
  return true;
}

}  // namespace glarecam::daemon
