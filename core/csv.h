// Minimal RFC 4180 CSV: splitting one line into fields (double-quoted fields may hold commas and
// doubled quotes) and quoting a field for writing. Records spanning lines are not supported:
// the sweep table (docs/stack-format.md) has none.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace glarecam {

// The fields of one CSV line (without its line break); an unterminated quote is kBadInput.
Result<std::vector<std::string>> splitCsvLine(std::string_view line);

// The field as written to CSV: quoted when it holds a comma, quote or line break.
std::string quoteCsvField(std::string_view field);

}  // namespace glarecam
