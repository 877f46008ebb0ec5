#include "core/spelling.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace glarecam {

std::size_t editDistance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic programme: the swap looks two rows back.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        current[j] = std::min(current[j], before[j - 2] + 1);
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<std::string> closestSpelling(std::string_view word,
                                           std::span<const std::string> candidates) {
  const std::size_t allowed = std::max<std::size_t>(1, word.size() / 3);
  std::size_t best = std::numeric_limits<std::size_t>::max();
  const std::string* closest = nullptr;
  const std::string* prefixed = nullptr;
  std::size_t prefix_count = 0;
  for (const std::string& candidate : candidates) {
    if (!word.empty() && (candidate.starts_with(word) || word.starts_with(candidate))) {
      prefixed = &candidate;
      ++prefix_count;
    }
    const std::size_t distance = editDistance(word, candidate);
    if (distance < best) {
      best = distance;
      closest = &candidate;
    }
  }
  if (closest && best <= allowed) return *closest;
  if (prefix_count == 1) return *prefixed;
  return std::nullopt;
}

}  // namespace glarecam
