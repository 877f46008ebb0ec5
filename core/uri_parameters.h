// Parameters of a device URI's id: "30,noise_g=0.001,seed=2" — a comma-separated list of
// KEY=VALUE items (optionally after a leading positional value), as the simulators' URIs take
// them. Errors name the URI ("camera URI sim:", "inclinometer URI sim:") given as `what`.
#pragma once

#include <functional>
#include <string_view>

#include "core/error.h"

namespace glarecam {

// A finite number, the whole text (no trailing characters).
Result<double> parseUriNumber(std::string_view text, std::string_view key, std::string_view what);

// Calls `apply(key, value)` for each KEY=VALUE item of `list`; stops at the first error.
Status forEachUriParameter(std::string_view list, std::string_view what,
                           const std::function<Status(std::string_view, std::string_view)>& apply);

}  // namespace glarecam
