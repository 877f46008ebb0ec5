// Typed, range-checked reads out of one table of a TOML file (the rig's glarecam.toml, a surface
// model's parameters). Every error is kBadInput and names FILE:LINE and the key ("rig.toml:12:
// schedule.interval_s = -1 is outside [1, 604800]"); a key nobody read is reported by
// checkNoUnknownKeys() as a typo. Shared by the rig's sections (rig/rig_config.cpp), the daemon's
// (daemon/daemon_config.cpp) and the surface files (surface/surface_catalogue.cpp).
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <expected>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace glarecam {

// Parses the TOML file at `path`, whose sub-tables must each be one of `sections` (the sections
// its readers know). kBadInput "FILE: no such file", "FILE:LINE: <TOML syntax error>" or
// "FILE:LINE: unknown section [x] (known: ...)".
Result<toml::table> readConfigFile(const std::filesystem::path& path,
                                   std::span<const std::string_view> sections);

class TableReader {
 public:
  // `name` is the table's name in messages ("gpio"; empty for the file's top level).
  TableReader(const std::filesystem::path& file, const toml::table& table, std::string name)
      : file_(file), table_(table), name_(std::move(name)) {}

  Result<std::optional<double>> number(const char* key, double min, double max);
  Result<double> requiredNumber(const char* key, double min, double max);
  // A whole number: a count or a time in whole units (a fraction would be silently cut).
  Result<std::optional<std::int64_t>> integer(const char* key, std::int64_t min, std::int64_t max);
  Result<std::optional<bool>> boolean(const char* key);
  Result<std::optional<std::string>> string(const char* key);
  Result<std::string> requiredString(const char* key);
  // A string that must be one of `choices`.
  Result<std::optional<std::string>> choice(const char* key,
                                            std::initializer_list<std::string_view> choices);
  // An array of numbers, each in [min, max], with min_count..max_count elements.
  Result<std::optional<std::vector<double>>> numberList(const char* key, double min, double max,
                                                        std::size_t min_count,
                                                        std::size_t max_count);
  // The node at `key` (marked as read), or nullptr: for keys of more than one type.
  const toml::node* node(const char* key);
  // A key read by the caller's own means (rig/: a GPIO line and its `_active_low`).
  void markUsed(const std::string& key) { used_.insert(key); }
  const toml::table& table() const { return table_; }

  // An error about the whole table: "FILE:LINE: [gpio] ...".
  std::unexpected<Error> tableError(const std::string& message) const;
  // An error about one value: "FILE:LINE: message", at the value's line.
  std::unexpected<Error> error(const toml::node& node, const std::string& message) const;

  // After all reads: a key nobody asked for is a typo or a key of another version.
  Status checkNoUnknownKeys() const;

  std::string qualified(std::string_view key) const;

 private:
  static int line(const toml::node& node) { return int(node.source().begin.line); }
  std::unexpected<Error> missing(const char* key) const;

  const std::filesystem::path& file_;
  const toml::table& table_;
  std::string name_;
  std::set<std::string> used_;
};

}  // namespace glarecam
