#include "brdf/brdf_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include "core/angles.h"
#include "core/csv.h"
#include "core/text_file.h"

namespace glarecam::brdf {

namespace {

// A number as the files write it ("30", "-1.5e-3", "+2"); nullopt when it is not one whole.
std::optional<double> parseNumber(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::vector<std::string_view> splitBlanks(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r' ||
                               line[i] == ',' || line[i] == ';'))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\r' ||
                                line[i] == ',' || line[i] == ';'))
      ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string_view::npos ? end : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return lines;
}

std::string lower(std::string_view text) {
  std::string out(text);
  std::ranges::transform(out, out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

// Blanks around a line or header (core's: the same blanks as the CSV reader's).
std::string trim(std::string_view text) { return trimCsvText(text); }

// The glarecam-wide cap on samples of one angle of incidence (a dense pab-opto scan: ~20 000).
constexpr std::size_t kMaxSamples = 2'000'000;

// ---- pab-opto ---------------------------------------------------------------------------------

Result<BrdfMeasurement> parsePabOpto(std::string_view text, const std::string& name) {
  BrdfMeasurement m;
  m.file = name;
  m.format = BrdfFileFormat::kPabOpto;
  std::optional<bool> is_dsf;
  std::optional<double> theta, phi;
  const std::vector<std::string_view> lines = splitLines(text);
  for (std::size_t index = 0; index < lines.size(); ++index) {
    const int line = static_cast<int>(index + 1);
    const auto fail = [&](const std::string& problem) {
      return badInput(fmt::format("{}:{}: {}", name, line, problem));
    };
    const std::string content = trim(lines[index]);
    if (content.empty()) continue;
    if (content.front() == '#') {
      const std::string header = trim(std::string_view(content).substr(1));
      const std::vector<std::string_view> words = splitBlanks(header);
      if (words.empty()) continue;
      const std::string key = lower(words.front());
      const auto number = [&](std::size_t i) -> Result<double> {
        if (i >= words.size()) return fail("#" + key + " needs a number");
        const std::optional<double> v = parseNumber(words[i]);
        if (!v || !std::isfinite(*v))
          return fail(fmt::format("#{}: \"{}\" is not a number", key, printableText(words[i])));
        return *v;
      };
      if (key == "format:" || key == "format") {
        // "#format: theta phi BSDF": the third word after the key says what the values are.
        const std::size_t kind_at = key == "format" && words.size() > 1 && words[1] == ":" ? 4 : 3;
        if (words.size() <= kind_at || lower(words[kind_at - 2]) != "theta" ||
            lower(words[kind_at - 1]) != "phi")
          return fail("#format must read \"theta phi BSDF\" or \"theta phi DSF\"");
        const std::string kind = lower(words[kind_at]);
        if (kind == "bsdf" || kind == "brdf") {
          is_dsf = false;
        } else if (kind == "dsf") {
          is_dsf = true;
        } else if (kind == "btdf") {
          return fail("BTDF data (transmission): glare is reflection, a BRDF is needed");
        } else {
          return fail(fmt::format("#format: unknown quantity \"{}\" (BSDF or DSF)",
                                  printableText(words[kind_at])));
        }
      } else if (key == "intheta" || key == "inphi" || key == "incident_angle") {
        // Each angle once, or again with the same value: two headers that disagree leave the
        // source's direction unknown.
        const auto set = [&](std::optional<double>& angle, std::size_t word,
                             const char* what) -> Status {
          double value = 0;
          GLARECAM_ASSIGN(value, number(word));
          if (angle && *angle != value)
            return fail(fmt::format("#{} gives {} {:g}°, an earlier header {:g}°", key, what, value,
                                    *angle));
          angle = value;
          return {};
        };
        const std::size_t expected = key == "incident_angle" ? 3 : 2;
        if (words.size() != expected)
          return fail(fmt::format("#{} takes {} number{}", key, expected - 1,
                                  expected == 3 ? "s (θ φ)" : ""));
        if (key != "inphi") GLARECAM_CHECK(set(theta, 1, "θ_i"));
        if (key == "inphi") GLARECAM_CHECK(set(phi, 1, "φ_i"));
        if (key == "incident_angle") GLARECAM_CHECK(set(phi, 2, "φ_i"));
      } else if (key == "upphi") {
        GLARECAM_CHECK(number(1));  // a common rotation of every azimuth: checked, not needed
      } else if (key == "colorimetry:" || key == "colorimetry") {
        const std::string value = words.size() > 1 ? lower(words.back()) : "";
        if (value != "cie-y")
          return fail(
              fmt::format("#colorimetry {}: only CIE-Y (luminance) data give a luminance picture",
                          words.size() > 1 ? printableText(words.back()) : "(empty)"));
      } else if (key == "sample_name") {
        const std::size_t open = header.find('"'), close = header.rfind('"');
        m.sample_name = open != std::string::npos && close > open
                            ? header.substr(open + 1, close - open - 1)
                            : trim(std::string_view(header).substr(words.front().size()));
      } else if (key == "relative_noise") {
        double noise = 0;
        GLARECAM_ASSIGN(noise, number(1));
        if (!(noise >= 0 && noise < 1))
          return fail("#relative_noise must be in [0, 1): a relative standard uncertainty");
        m.relative_noise = noise;
      }
      continue;  // other comments and keys are the instrument's
    }
    if (!is_dsf) return fail("data before \"#format: theta phi BSDF|DSF\" (not a pab-opto file?)");
    if (!theta || !phi)
      return fail("data before the angle of incidence (#intheta and #inphi, or #incident_angle)");
    const std::vector<std::string_view> words = splitBlanks(content);
    if (words.size() != 3)
      return fail(
          fmt::format("a sample row is \"theta phi value\", this one has {} fields", words.size()));
    double v[3];
    for (int i = 0; i < 3; ++i) {
      const std::optional<double> x = parseNumber(words[i]);
      if (!x) return fail(fmt::format("\"{}\" is not a number", printableText(words[i])));
      if (!std::isfinite(*x)) return fail(fmt::format("{} is not finite", printableText(words[i])));
      v[i] = *x;
    }
    if (v[0] < 0) return fail(fmt::format("θ {:g}° is negative", v[0]));
    if (v[0] > 90)
      return fail(fmt::format(
          "θ {:g}° lies behind the sample: transmission (BTDF) data, a BRDF is needed", v[0]));
    if (v[2] < 0) return fail(fmt::format("negative value {:g}", v[2]));
    double value = v[2];
    if (*is_dsf) {
      const double c = std::cos(radians(v[0]));
      constexpr double kMinCos = 1e-6;  // θ 90°: a DSF there says nothing about the BRDF
      if (c < kMinCos) continue;
      value /= c;
    }
    if (m.samples.size() >= kMaxSamples)
      return fail(fmt::format("more than {} samples", kMaxSamples));
    const double wrapped = std::fmod(std::fmod(v[1], 360.0) + 360.0, 360.0);
    m.samples.push_back({v[0], wrapped, value, line});
  }
  if (!is_dsf) return badInput(name + ": no \"#format: theta phi BSDF|DSF\" header");
  if (!theta || !phi)
    return badInput(name + ": no angle of incidence (#intheta and #inphi, or #incident_angle)");
  if (!(*theta >= 0 && *theta <= kMaxIncidentThetaDeg))
    return badInput(fmt::format("{}: angle of incidence {:g}° is outside [0, {:g}]°", name, *theta,
                                kMaxIncidentThetaDeg));
  if (m.samples.empty()) return badInput(name + ": no samples");
  m.incident_theta_deg = *theta;
  m.incident_phi_deg = std::fmod(std::fmod(*phi, 360.0) + 360.0, 360.0);
  return m;
}

// ---- Zemax ------------------------------------------------------------------------------------

struct Token {
  std::string_view text;
  int line = 0;
};

std::vector<Token> zemaxTokens(std::string_view text) {
  std::vector<Token> tokens;
  const std::vector<std::string_view> lines = splitLines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string_view line = lines[i];
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    for (std::string_view word : splitBlanks(line))
      tokens.push_back({word, static_cast<int>(i + 1)});
  }
  return tokens;
}

class ZemaxParser {
 public:
  ZemaxParser(std::string_view text, std::string name)
      : tokens_(zemaxTokens(text)), name_(std::move(name)) {}

  Result<std::vector<BrdfMeasurement>> parse();

 private:
  std::unexpected<Error> fail(int line, const std::string& problem) const {
    return badInput(fmt::format("{}:{}: {}", name_, line, problem));
  }
  int line() const { return at_ < tokens_.size() ? tokens_[at_].line : lastLine(); }
  int lastLine() const { return tokens_.empty() ? 1 : tokens_.back().line; }
  Result<std::string_view> word(const char* what) {
    if (at_ >= tokens_.size()) return fail(lastLine(), fmt::format("ends before {}", what));
    return tokens_[at_++].text;
  }
  Result<double> number(const char* what) {
    std::string_view text;
    const int at_line = line();
    GLARECAM_ASSIGN(text, word(what));
    const std::optional<double> v = parseNumber(text);
    if (!v)
      return fail(at_line, fmt::format("{}: \"{}\" is not a number", what, printableText(text)));
    if (!std::isfinite(*v))
      return fail(at_line, fmt::format("{}: {} is not finite", what, printableText(text)));
    return *v;
  }
  // "Keyword N v1 … vN", angles in [low, high] and ascending.
  Result<std::vector<double>> angleList(const char* what, double low, double high) {
    const int at_line = line();
    double count = 0;
    GLARECAM_ASSIGN(count, number(what));
    constexpr double kMaxAngles = 100'000;
    if (!(count >= 1 && count <= kMaxAngles && count == std::floor(count)))
      return fail(at_line, fmt::format("{}: the count {:g} is not a whole number in [1, {:g}]",
                                       what, count, kMaxAngles));
    std::vector<double> values;
    for (int i = 0; i < static_cast<int>(count); ++i) {
      const int value_line = line();
      double v = 0;
      GLARECAM_ASSIGN(v, number(what));
      if (v < low || v > high)
        return fail(value_line,
                    fmt::format("{} {:g}° is outside [{:g}, {:g}]°", what, v, low, high));
      if (!values.empty() && v <= values.back())
        return fail(value_line,
                    fmt::format("{} must ascend: {:g}° after {:g}°", what, v, values.back()));
      values.push_back(v);
    }
    return values;
  }

  std::vector<Token> tokens_;
  std::string name_;
  std::size_t at_ = 0;
};

Result<std::vector<BrdfMeasurement>> ZemaxParser::parse() {
  std::optional<bool> plane_symmetric, brdf;
  bool xyz = false;
  std::vector<double> rotations{0}, incidences, azimuths, radials;
  bool have_incidence = false, have_azimuth = false, have_radial = false;
  // Header: keywords up to the first data block.
  while (at_ < tokens_.size()) {
    const Token keyword = tokens_[at_];
    if (keyword.text == "Monochrome" || keyword.text.starts_with("Tristimulus") ||
        keyword.text == "DataBegin")
      break;
    ++at_;
    std::string_view value;
    if (keyword.text == "Source") {
      GLARECAM_ASSIGN(value, word("Source"));
    } else if (keyword.text == "Symmetry") {
      GLARECAM_ASSIGN(value, word("Symmetry"));
      if (value == "PlaneSymmetrical") {
        plane_symmetric = true;
      } else if (value == "Asymmetrical") {
        plane_symmetric = false;
      } else {
        return fail(keyword.line, fmt::format("Symmetry {}: PlaneSymmetrical or Asymmetrical "
                                              "(a 4-D table is not supported)",
                                              printableText(value)));
      }
    } else if (keyword.text == "SpectralContent") {
      GLARECAM_ASSIGN(value, word("SpectralContent"));
      if (value == "XYZ") {
        xyz = true;
      } else if (value != "Monochrome") {
        return fail(keyword.line,
                    fmt::format("SpectralContent {}: Monochrome or XYZ", printableText(value)));
      }
    } else if (keyword.text == "ScatterType") {
      GLARECAM_ASSIGN(value, word("ScatterType"));
      if (value == "BTDF")
        return fail(keyword.line,
                    "ScatterType BTDF (transmission): glare is reflection, a BRDF is needed");
      if (value != "BRDF")
        return fail(keyword.line, fmt::format("ScatterType {}: BRDF", printableText(value)));
      brdf = true;
    } else if (keyword.text == "SampleRotation") {
      GLARECAM_ASSIGN(rotations, angleList("SampleRotation", 0, 360));
    } else if (keyword.text == "AngleOfIncidence") {
      GLARECAM_ASSIGN(incidences, angleList("AngleOfIncidence", 0, kMaxIncidentThetaDeg));
      have_incidence = true;
    } else if (keyword.text == "ScatterAzimuth") {
      GLARECAM_ASSIGN(azimuths, angleList("ScatterAzimuth", 0, 360));
      have_azimuth = true;
    } else if (keyword.text == "ScatterRadial") {
      GLARECAM_ASSIGN(radials, angleList("ScatterRadial", 0, 90));
      have_radial = true;
    } else {
      return fail(keyword.line, fmt::format("unknown keyword \"{}\"", printableText(keyword.text)));
    }
  }
  const int header_end = line();
  if (!brdf) return fail(header_end, "no \"ScatterType BRDF\" before the data");
  if (!plane_symmetric) return fail(header_end, "no Symmetry before the data");
  if (!have_incidence || !have_azimuth || !have_radial)
    return fail(header_end,
                "AngleOfIncidence, ScatterAzimuth and ScatterRadial must come before the data");
  if (*plane_symmetric && azimuths.back() > 180)
    return fail(
        header_end,
        fmt::format("a PlaneSymmetrical table's azimuths end at 180°, not {:g}°", azimuths.back()));
  const std::size_t per_block = azimuths.size() * radials.size();
  if (per_block > kMaxSamples)
    return fail(header_end, fmt::format("{} values a block, more than {}", per_block, kMaxSamples));

  std::vector<BrdfMeasurement> out;
  for (double rotation : rotations)
    for (double incidence : incidences) {
      BrdfMeasurement m;
      m.file = name_;
      m.format = BrdfFileFormat::kZemax;
      m.incident_theta_deg = incidence;
      m.incident_phi_deg = rotation;
      out.push_back(std::move(m));
    }
  bool read_y = false;
  // Data: "Monochrome"/"TristimulusX|Y|Z", then DataBegin, per block TIS and the rows, DataEnd.
  while (at_ < tokens_.size()) {
    const Token channel = tokens_[at_++];
    bool keep = true;
    if (channel.text == "Monochrome") {
      if (xyz) return fail(channel.line, "a Monochrome block in an XYZ table");
    } else if (channel.text == "TristimulusX" || channel.text == "TristimulusZ") {
      keep = false;
    } else if (channel.text == "TristimulusY") {
    } else if (channel.text != "DataBegin") {
      return fail(channel.line,
                  fmt::format("expected a data block, not \"{}\"", printableText(channel.text)));
    }
    if (channel.text != "DataBegin") {
      std::string_view begin;
      const int begin_line = line();
      GLARECAM_ASSIGN(begin, word("DataBegin"));
      if (begin != "DataBegin")
        return fail(begin_line,
                    fmt::format("expected DataBegin, not \"{}\"", printableText(begin)));
    }
    if (keep && read_y) return fail(channel.line, "a second block of luminance data");
    for (BrdfMeasurement& m : out) {
      std::string_view tis;
      const int tis_line = line();
      GLARECAM_ASSIGN(tis, word("TIS"));
      if (tis != "TIS")
        return fail(tis_line, fmt::format("expected TIS for the block of θ_i {:g}°, not \"{}\"",
                                          m.incident_theta_deg, printableText(tis)));
      GLARECAM_CHECK(number("TIS"));
      for (double azimuth : azimuths)
        for (double radial : radials) {
          const int value_line = line();
          double value = 0;
          GLARECAM_ASSIGN(value, number("a BRDF value"));
          if (value < 0) return fail(value_line, fmt::format("negative value {:g}", value));
          if (!keep) continue;
          // The specular direction once, not once per azimuth.
          if (radial == 0 && azimuth != azimuths.front()) continue;
          const SpecularFrame frame(m.incident_theta_deg, m.incident_phi_deg);
          const int copies = *plane_symmetric && azimuth > 0 && azimuth < 180 ? 2 : 1;
          for (int copy = 0; copy < copies; ++copy) {
            const double a = copy == 0 ? azimuth : 360 - azimuth;
            const auto [theta, phi] = frame.fromFrame(zemaxScatterRay(radial, a));
            constexpr double kHorizonDeg = 90.0;  // directions behind the sample carry no data
            if (theta >= kHorizonDeg) continue;
            m.samples.push_back({theta, phi, value, value_line});
          }
        }
    }
    std::string_view end;
    const int end_line = line();
    GLARECAM_ASSIGN(end, word("DataEnd"));
    if (end != "DataEnd")
      return fail(end_line, fmt::format("expected DataEnd after {} values a block, not \"{}\"",
                                        per_block, printableText(end)));
    read_y = read_y || keep;
  }
  if (!read_y) return fail(lastLine(), xyz ? "no TristimulusY block" : "no data block");
  return out;
}

constexpr std::string_view kZemaxKeywords[] = {
    "Source",         "Symmetry",         "SpectralContent", "ScatterType",
    "SampleRotation", "AngleOfIncidence", "ScatterAzimuth",  "ScatterRadial"};

}  // namespace

calibration::Ray zemaxScatterRay(double radial_deg, double azimuth_deg) {
  const double r = radians(radial_deg), a = radians(azimuth_deg);
  return {std::sin(r) * std::sin(a), std::sin(r) * std::cos(a), std::cos(r)};
}

Result<std::vector<BrdfMeasurement>> parseBrdfText(std::string_view text, const std::string& name) {
  // What the file is, from its first words: Zemax keywords, or pab-opto '#' headers.
  if (text.find("<WindowElement") != std::string_view::npos ||
      text.find("LBNL/Klems") != std::string_view::npos)
    return badInput(
        name +
        ":1: a window BSDF in the Klems basis: its 145 patches are 5–15° wide, too coarse for a "
        "glare spot a few degrees wide; give the goniophotometer's own data (pab-opto or Zemax "
        "BSDF text, docs/brdf.md)");
  for (const Token& token : zemaxTokens(text.substr(0, std::min<std::size_t>(text.size(), 4096)))) {
    if (std::ranges::find(kZemaxKeywords, token.text) != std::end(kZemaxKeywords))
      return ZemaxParser(text, name).parse();
    break;
  }
  const std::string head = lower(text.substr(0, std::min<std::size_t>(text.size(), 65536)));
  if (head.find("#format") != std::string::npos || head.find("#intheta") != std::string::npos ||
      head.find("#incident_angle") != std::string::npos) {
    BrdfMeasurement m;
    GLARECAM_ASSIGN(m, parsePabOpto(text, name));
    return std::vector<BrdfMeasurement>{std::move(m)};
  }
  return badInput(name +
                  ":1: unknown BRDF format: neither pab-opto/Radiance text (\"#format: theta phi "
                  "BSDF\") nor a Zemax BSDF file (\"ScatterType BRDF\"); docs/brdf.md");
}

Result<std::vector<BrdfMeasurement>> readBrdfFile(const std::filesystem::path& path) {
  std::string text;
  GLARECAM_ASSIGN(text, readTextFile(path, kMaxBrdfFileBytes, "a BRDF file"));
  return parseBrdfText(text, path.string());
}

std::string formatPabOpto(const BrdfMeasurement& m) {
  std::string out;
  if (!m.sample_name.empty()) out += fmt::format("#sample_name \"{}\"\n", m.sample_name);
  out += "#format: theta phi BSDF\n";
  out += fmt::format("#incident_angle {:.10g} {:.10g}\n", m.incident_theta_deg, m.incident_phi_deg);
  out +=
      fmt::format("#intheta {:.10g}\n#inphi {:.10g}\n", m.incident_theta_deg, m.incident_phi_deg);
  out += "#upphi 0\n#colorimetry: CIE-Y\n";
  if (m.relative_noise) out += fmt::format("#relative_noise {:.6g}\n", *m.relative_noise);
  for (const BrdfSample& s : m.samples)
    out += fmt::format("{:.8g}\t{:.8g}\t{:.8g}\n", s.theta_deg, s.phi_deg, s.brdf_sr);
  return out;
}

std::string formatZemaxBsdf(const ZemaxTable& t) {
  std::string out = "# BSDF data interchange file (written by glarecam)\n";
  out += fmt::format("Source {}\nSymmetry {}\nSpectralContent Monochrome\nScatterType BRDF\n",
                     t.source, t.plane_symmetric ? "PlaneSymmetrical" : "Asymmetrical");
  out += "SampleRotation 1\n0\n";
  const auto list = [&](const char* keyword, const std::vector<double>& values) {
    out += fmt::format("{} {}\n", keyword, values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
      out += fmt::format("{:.10g}{}", values[i], i + 1 < values.size() ? "\t" : "\n");
  };
  std::vector<double> incidences;
  for (const ZemaxTable::Block& b : t.blocks) incidences.push_back(b.incident_theta_deg);
  list("AngleOfIncidence", incidences);
  list("ScatterAzimuth", t.azimuth_deg);
  list("ScatterRadial", t.radial_deg);
  out += "Monochrome\nDataBegin\n";
  for (const ZemaxTable::Block& b : t.blocks) {
    out += fmt::format("TIS {:.6g}\n", b.tis);
    for (std::size_t a = 0; a < t.azimuth_deg.size(); ++a)
      for (std::size_t r = 0; r < t.radial_deg.size(); ++r)
        out += fmt::format("{:.8g}{}", b.values[a * t.radial_deg.size() + r],
                           r + 1 < t.radial_deg.size() ? "\t" : "\n");
  }
  out += "DataEnd\n";
  return out;
}

}  // namespace glarecam::brdf
