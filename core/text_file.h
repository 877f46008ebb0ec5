// Reading a whole file as text, with the one-line errors every reader gives: kBadInput naming
// the file when it is missing, not a regular file, cannot be opened or is larger than the caller
// allows; kIo when reading it fails.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>

#include "core/error.h"

namespace glarecam {

inline constexpr std::uintmax_t kNoFileSizeLimit = std::numeric_limits<std::uintmax_t>::max();

// `what` names the kind of file in the size error ("a BRDF file": "PATH: 80 MB, more than the
// 64 MB a BRDF file may have").
Result<std::string> readTextFile(const std::filesystem::path& path,
                                 std::uintmax_t max_bytes = kNoFileSizeLimit,
                                 std::string_view what = "the file");

// A file's text as a one-line message quotes it: control bytes (a NUL would end the message, a
// line break split it) as '?', at most kQuotedTextChars bytes, then "...".
inline constexpr std::size_t kQuotedTextChars = 40;
std::string printableText(std::string_view text);

}  // namespace glarecam
