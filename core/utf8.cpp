#include "core/utf8.h"

#include <string>

namespace glarecam {

Status requireUtf8(std::string_view text, std::string_view what) {
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const int continuation = lead < 0x80           ? 0
                             : (lead >> 5) == 0x6  ? 1
                             : (lead >> 4) == 0xE  ? 2
                             : (lead >> 3) == 0x1E ? 3
                                                   : -1;
    bool ok = continuation >= 0 && i + continuation < text.size();
    for (int k = 1; ok && k <= continuation; ++k)
      ok = (static_cast<unsigned char>(text[i + k]) >> 6) == 0x2;
    if (!ok) return badInput(std::string(what) + ": not valid UTF-8 text");
    i += continuation + 1;
  }
  return {};
}

}  // namespace glarecam
