// Text that goes into documents (a module name on the data sheet, a JSON string) must be valid
// UTF-8: Cairo and the JSON writer refuse anything else, and would fail late, mid-write.
#pragma once

#include <string_view>

#include "core/error.h"

namespace glarecam {

// kBadInput "<what>: not valid UTF-8 text" unless `text` has UTF-8's byte structure (RFC 3629: a
// lead byte, then as many 10xxxxxx continuation bytes as it announces).
Status requireUtf8(std::string_view text, std::string_view what);

}  // namespace glarecam
