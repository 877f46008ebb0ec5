// "Did you mean": the known name closest to a misspelt one, for the command lines' unknown
// options and commands.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace glarecam {

// The number of single-character insertions, deletions, substitutions and swaps of neighbours
// that turn `a` into `b` (optimal string alignment distance).
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate closest to `word`, when it is close enough to be what was meant: at most a third
// of the word's characters (and at least one) edited, or else the one candidate that `word` begins
// or that begins `word` ("--calib" for --calibration, "--output" for --out). Ties go to the first.
std::optional<std::string> closestSpelling(std::string_view word,
                                           std::span<const std::string> candidates);

}  // namespace glarecam
