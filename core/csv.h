// Minimal RFC 4180 CSV: splitting one line into fields (double-quoted fields may hold commas and
// doubled quotes) and quoting a field for writing. Records spanning lines are not supported:
// the sweep table (docs/stack-format.md) has none.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace glarecam {

// The fields of one CSV line (without its line break); an unterminated quote is kBadInput.
Result<std::vector<std::string>> splitCsvLine(std::string_view line);

// The field as written to CSV: quoted when it holds a comma, quote or line break.
std::string quoteCsvField(std::string_view field);

// `text` without leading and trailing blanks (spaces, tabs, carriage returns).
std::string trimCsvText(std::string_view text);

// Reads the CSV file `path` (a `what`, e.g. "sweep table", for messages) line by line: a UTF-8
// byte-order mark (spreadsheets write one) dropped, each line trimmed, empty lines skipped; a
// '#' line goes to `on_comment` (its text after '#', trimmed), any other is split into fields
// for `on_record`. An error of the splitting or of either callback is returned prefixed
// "PATH:LINE: "; a directory or an unreadable file is kBadInput naming it.
Status readCsvFile(const std::filesystem::path& path, std::string_view what,
                   const std::function<Status(std::vector<std::string>& fields)>& on_record,
                   const std::function<void(std::string comment)>& on_comment = {});

}  // namespace glarecam
