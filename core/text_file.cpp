#include "core/text_file.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace glarecam {

Result<std::string> readTextFile(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                 std::string_view what) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return badInput(name + ": file is missing or not a regular file");
  if (max_bytes != kNoFileSizeLimit) {
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) return ioError(name + ": cannot read its size: " + ec.message());
    if (size > max_bytes)
      return badInput(fmt::format("{}: {} MB, more than the {} MB {} may have", name, size >> 20,
                                  max_bytes >> 20, what));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return badInput(name + ": cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return ioError(name + ": read failed");
  return std::move(text).str();
}

std::string printableText(std::string_view text) {
  std::string out(text.substr(0, kQuotedTextChars));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return text.size() > kQuotedTextChars ? out + "..." : out;
}

}  // namespace glarecam
