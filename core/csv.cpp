#include "core/csv.h"

#include <fmt/format.h>

#include <fstream>

namespace glarecam {

Result<std::vector<std::string>> splitCsvLine(std::string_view line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c != '"') {
        fields.back() += c;
      } else if (i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else {
        quoted = false;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (quoted) return badInput("unterminated quoted field");
  return fields;
}

std::string quoteCsvField(std::string_view field) {
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(field);
  std::string quoted = "\"";
  for (char c : field) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

std::string trimCsvText(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return std::string(text.substr(first, last - first + 1));
}

Status readCsvFile(const std::filesystem::path& path, std::string_view what,
                   const std::function<Status(std::vector<std::string>& fields)>& on_record,
                   const std::function<void(std::string comment)>& on_comment) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return badInput(fmt::format("{}: a directory, not a {} (CSV)", path.string(), what));
  std::ifstream in(path);
  if (!in) return badInput(fmt::format("{}: cannot open the {}", path.string(), what));
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";
    if (number == 1 && line.starts_with(kUtf8ByteOrderMark))
      line.erase(0, kUtf8ByteOrderMark.size());
    const std::string text = trimCsvText(line);
    if (text.empty()) continue;
    if (text.front() == '#') {
      if (on_comment) on_comment(trimCsvText(std::string_view(text).substr(1)));
      continue;
    }
    const std::string where = fmt::format("{}:{}", path.string(), number);
    auto fields = splitCsvLine(text);
    if (!fields) return std::unexpected(withContext(fields.error(), where));
    if (const Status done = on_record(*fields); !done)
      return std::unexpected(withContext(done.error(), where));
  }
  if (in.bad()) return ioError(path.string() + ": read failed");
  return {};
}

}  // namespace glarecam
