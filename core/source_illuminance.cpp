#include "core/source_illuminance.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

namespace glarecam {
namespace {

constexpr std::string_view kOriginWords[] = {"sensor", "given", "clear_sky"};

// A whole field of `text` as a number, or none (trailing text, no digits, not finite).
std::optional<double> wholeNumber(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (text.empty()) return std::nullopt;
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

Status checkIlluminance(double lx, const std::string& what) {
  if (!std::isfinite(lx) || lx <= 0)
    return badInput(fmt::format("{} {} lx must be finite and positive", what, lx));
  if (lx > kMaxSourceIlluminanceLx)
    return badInput(fmt::format(
        "{} {} lx is above {} lx, more than any sun gives (a W/m² or klx value read as lx?)", what,
        lx, kMaxSourceIlluminanceLx));
  return {};
}

}  // namespace

std::string_view originWord(IlluminanceOrigin origin) {
  return kOriginWords[static_cast<int>(origin)];
}

std::optional<IlluminanceOrigin> originFromWord(std::string_view word) {
  for (int i = 0; i < 3; ++i)
    if (kOriginWords[i] == word) return static_cast<IlluminanceOrigin>(i);
  return std::nullopt;
}

Result<SourceIlluminance> parseSourceIlluminance(const JsonReader& block) {
  GLARECAM_CHECK(block.object());
  SourceIlluminance source;
  GLARECAM_ASSIGN(source.illuminance_lx, block.number("illuminance_lx"));
  if (Status ok = checkIlluminance(source.illuminance_lx, "is"); !ok)
    return block.fail("illuminance_lx", ok.error().message);
  std::optional<double> u;
  GLARECAM_ASSIGN(u, block.optionalNonNegative("illuminance_u_lx"));
  source.illuminance_u_lx = u.value_or(0);
  std::string word;
  GLARECAM_ASSIGN(word, block.word("origin", {"sensor", "given", "clear_sky"}));
  source.origin = *originFromWord(word);
  GLARECAM_ASSIGN(source.instrument, block.optionalText("instrument"));
  if (block.has("samples")) {
    long long samples = 0;
    GLARECAM_ASSIGN(samples, block.integer("samples", 1, 1'000'000));
    source.samples = static_cast<int>(samples);
  }
  GLARECAM_ASSIGN(source.spread_lx, block.optionalNonNegative("spread_lx"));
  return source;
}

nlohmann::json toJson(const SourceIlluminance& source) {
  nlohmann::json block = {{"illuminance_lx", source.illuminance_lx},
                          {"illuminance_u_lx", source.illuminance_u_lx},
                          {"origin", originWord(source.origin)}};
  if (source.instrument) block["instrument"] = *source.instrument;
  if (source.samples) block["samples"] = *source.samples;
  if (source.spread_lx) block["spread_lx"] = *source.spread_lx;
  return block;
}

Result<SourceIlluminance> parseGivenIlluminance(std::string_view text, const std::string& where) {
  const std::string quoted = fmt::format("{} \"{}\"", where, text);
  std::string_view value_text = text;
  std::string_view u_text;
  for (std::string_view sign : {"±", "+/-", "+-"}) {
    if (const std::size_t at = text.find(sign); at != std::string_view::npos) {
      value_text = text.substr(0, at);
      u_text = text.substr(at + sign.size());
      if (u_text.empty())
        return badInput(quoted + ": the uncertainty after " + std::string(sign) + " is missing");
      break;
    }
  }
  const std::optional<double> lx = wholeNumber(value_text);
  if (!lx) return badInput(quoted + ": expected an illuminance in lx, as 92500 or 92500±2800");
  SourceIlluminance source;
  source.illuminance_lx = *lx;
  source.origin = IlluminanceOrigin::kGiven;
  if (Status ok = checkIlluminance(*lx, "the illuminance"); !ok)
    return badInput(quoted + ": " + ok.error().message);
  if (!u_text.empty()) {
    const std::optional<double> u = wholeNumber(u_text);
    if (!u || !std::isfinite(*u) || *u < 0)
      return badInput(quoted + ": the uncertainty must be a number >= 0 (lx)");
    if (*u >= *lx)
      return badInput(quoted + ": the uncertainty is at least as large as the illuminance itself");
    source.illuminance_u_lx = *u;
  }
  return source;
}

Status checkReferenceIlluminance(double reference_lx, const std::string& where) {
  if (Status ok = checkIlluminance(reference_lx, "the reference illuminance"); !ok)
    return badInput(where + ": " + ok.error().message);
  return {};
}

std::string describe(const SourceIlluminance& source) {
  return fmt::format("{:.1f} ± {:.1f} klx ({})", source.illuminance_lx / 1000,
                     source.illuminance_u_lx / 1000, originWord(source.origin));
}

}  // namespace glarecam
