// Parsers for compound option values ("1224x1024", "0.1,-0.05,0,0,0"), returning kBadInput
// errors that name the option.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/source_illuminance.h"

namespace glarecam::apps {

Result<std::uint64_t> parseUnsigned(const std::string& text, const std::string& option);
Result<std::pair<int, int>> parseSize(const std::string& text, const std::string& option);
// A path option that was given must not be empty ("--out $UNSET" is a mistake, not a default).
Status requireNonEmptyPath(const std::optional<std::string>& value, const std::string& option);

// The number of an option that was given (nullopt when it was not).
Result<std::optional<double>> parseOptionalNumber(const std::optional<std::string>& text,
                                                  const std::string& option);
// The same for a luminance in cd/m², which must be positive (a --threshold).
Result<std::optional<double>> parseOptionalLuminance(const std::optional<std::string>& text,
                                                     const std::string& option);

// --source-illuminance LX[±U] (origin given), when it was given.
Result<std::optional<SourceIlluminance>> parseOptionalSourceIlluminance(
    const std::optional<std::string>& text, const std::string& option);
// --reference-illuminance LX, or the default E_ref when it was not given.
Result<double> parseReferenceIlluminance(const std::optional<std::string>& text,
                                         const std::string& option);
// The help text of both, one wording for every command that takes them.
inline constexpr const char* kSourceIlluminanceHelp =
    "the source's direct normal illuminance during the bracket in lx, with its standard "
    "uncertainty: 92500±2800 (or 92500+-2800); refers the stack's luminances to the reference "
    "illuminance (docs/method.md)";
inline constexpr const char* kMixedReferencesHelp =
    "fit rows referred to different illuminances, or referred and unreferred rows, together "
    "(default: refused, naming the rows)";
inline constexpr const char* kReferenceIlluminanceHelp =
    "the illuminance in lx every luminance is referred to (default 100000)";

Result<std::vector<double>> parseNumberList(const std::string& text, const std::string& option,
                                            std::size_t min_count, std::size_t max_count);

}  // namespace glarecam::apps
