#include "core/time.h"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <optional>

namespace glarecam {
namespace {

using namespace std::chrono;

// Reads the text left to right; each read either consumes what it expects or leaves the cursor.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}

  bool atEnd() const { return position_ == text_.size(); }
  char peek() const { return atEnd() ? '\0' : text_[position_]; }
  bool consume(char c) {
    if (peek() != c) return false;
    ++position_;
    return true;
  }
  // Exactly `count` digits as a number, or nothing.
  std::optional<long> digits(std::size_t count) {
    if (text_.size() - position_ < count) return std::nullopt;
    long value = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const char c = text_[position_ + i];
      if (c < '0' || c > '9') return std::nullopt;
      value = value * 10 + (c - '0');
    }
    position_ += count;
    return value;
  }
  // All the digits from here (at least one), as text.
  std::string_view digitRun() {
    const std::size_t start = position_;
    while (peek() >= '0' && peek() <= '9') ++position_;
    return text_.substr(start, position_ - start);
  }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
};

std::string_view trim(std::string_view text) {
  const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

}  // namespace

Result<UtcTime> parseIsoTime(std::string_view raw_text) {
  const std::string_view text = trim(raw_text);
  const std::string quoted = "time \"" + std::string(raw_text) + "\"";
  const auto malformed = [&](const std::string& what) {
    return badInput(quoted + ": " + what +
                    " (expected ISO 8601 such as 2003-10-17T19:30:30Z or "
                    "2003-10-17T12:30:30-07:00)");
  };
  Cursor cursor(text);

  // Date: YYYY-MM-DD, or ±YYYY... for years outside 0000..9999.
  int sign = 1;
  const bool signed_year = cursor.peek() == '+' || cursor.peek() == '-';
  if (cursor.consume('-')) {
    sign = -1;
  } else {
    cursor.consume('+');
  }
  const std::string_view year_digits = cursor.digitRun();
  if (year_digits.size() < 4 || (!signed_year && year_digits.size() != 4) ||
      year_digits.size() > 5) {
    return malformed("no 4-digit year");
  }
  const long year = sign * std::strtol(std::string(year_digits).c_str(), nullptr, 10);
  std::optional<long> month, day;
  if (!cursor.consume('-') || !(month = cursor.digits(2)) || !cursor.consume('-') ||
      !(day = cursor.digits(2))) {
    return malformed("no date YYYY-MM-DD");
  }
  const year_month_day date{std::chrono::year{static_cast<int>(year)},
                            std::chrono::month{static_cast<unsigned>(*month)},
                            std::chrono::day{static_cast<unsigned>(*day)}};
  if (!date.ok()) return badInput(quoted + ": no such date");

  // Time of day: hh:mm[:ss[.fraction]].
  if (!cursor.consume('T') && !cursor.consume('t') && !cursor.consume(' ')) {
    return malformed("no time of day after the date");
  }
  std::optional<long> hour, minute, second = 0;
  if (!(hour = cursor.digits(2)) || !cursor.consume(':') || !(minute = cursor.digits(2))) {
    return malformed("no time hh:mm:ss");
  }
  const bool has_seconds = cursor.consume(':');
  if (has_seconds && !(second = cursor.digits(2))) return malformed("no seconds after ':'");
  if (*hour > 23) return badInput(quoted + ": hour " + std::to_string(*hour) + " is not 00..23");
  if (*minute > 59) {
    return badInput(quoted + ": minute " + std::to_string(*minute) + " is not 00..59");
  }
  if (*second > 59) {
    return badInput(quoted + ": second " + std::to_string(*second) +
                    " is not 00..59 (leap seconds are not supported)");
  }
  microseconds fraction{0};
  if (cursor.consume('.') || cursor.consume(',')) {
    // ISO 8601 reads 12:30.5 as half a minute; a fraction is taken after the seconds only.
    if (!has_seconds) return malformed("a fraction is allowed after the seconds only (hh:mm:ss.s)");
    const std::string_view fraction_digits = cursor.digitRun();
    if (fraction_digits.empty() || fraction_digits.size() > 9) {
      return malformed("a fraction of a second needs 1 to 9 digits");
    }
    long nanoseconds = 0;
    for (std::size_t i = 0; i < 9; ++i) {
      nanoseconds = nanoseconds * 10 + (i < fraction_digits.size() ? fraction_digits[i] - '0' : 0);
    }
    fraction = microseconds{(nanoseconds + 500) / 1000};
  }

  // Zone: Z, or an offset from UTC.
  if (cursor.atEnd()) {
    return badInput(quoted +
                    ": no time zone; add \"Z\" for UTC or the offset from UTC such as "
                    "\"-07:00\" (a local time read as UTC would put the sun in the wrong place)");
  }
  minutes offset{0};
  if (cursor.consume('Z') || cursor.consume('z')) {
    // UTC
  } else if (cursor.peek() == '+' || cursor.peek() == '-') {
    const int offset_sign = cursor.peek() == '-' ? -1 : 1;
    cursor.consume(cursor.peek());
    std::optional<long> offset_hours = cursor.digits(2), offset_minutes = 0;
    if (!offset_hours) return malformed("no offset hours after the sign");
    if (cursor.consume(':')) {
      if (!(offset_minutes = cursor.digits(2))) return malformed("no offset minutes after ':'");
    } else if (!cursor.atEnd()) {
      if (!(offset_minutes = cursor.digits(2))) return malformed("bad offset");
    }
    if (*offset_minutes > 59 || *offset_hours * 60 + *offset_minutes > 18 * 60) {
      return badInput(quoted + ": offset from UTC is beyond ±18:00");
    }
    offset = offset_sign * minutes{*offset_hours * 60 + *offset_minutes};
  } else {
    return malformed("no time zone");
  }
  if (!cursor.atEnd()) return malformed("unexpected text after the time zone");

  const UtcTime local =
      sys_days{date} + hours{*hour} + minutes{*minute} + seconds{*second} + fraction;
  return local - offset;
}

std::string formatIsoTime(UtcTime utc) {
  const sys_days day = floor<days>(utc);
  const year_month_day date{day};
  const hh_mm_ss<microseconds> time{utc - day};
  const int year = static_cast<int>(date.year());
  char text[64];
  const int length = std::snprintf(
      text, sizeof text,
      year >= 0 && year <= 9999 ? "%04d-%02u-%02uT%02ld:%02ld:%02lld"
                                : "%+05d-%02u-%02uT%02ld:%02ld:%02lld",
      year, static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()),
      static_cast<long>(time.hours().count()), static_cast<long>(time.minutes().count()),
      static_cast<long long>(time.seconds().count()));
  std::string result(text, static_cast<std::size_t>(length));
  const long long fraction_us = time.subseconds().count();
  if (fraction_us != 0) {
    char fraction[16];
    std::snprintf(fraction, sizeof fraction, ".%06lld", fraction_us);
    std::string digits(fraction);
    while (digits.back() == '0') digits.pop_back();
    result += digits;
  }
  return result + "Z";
}

std::string formatIsoSeconds(UtcTime utc) {
  return formatIsoTime(std::chrono::floor<std::chrono::seconds>(utc));
}

namespace {

// Exactly `count` digits of `text` from `at`, as a number, or nullopt.
std::optional<unsigned> fixedDigits(std::string_view text, std::size_t at, std::size_t count) {
  if (text.size() < at + count) return std::nullopt;
  unsigned value = 0;
  for (std::size_t i = at; i < at + count; ++i) {
    if (text[i] < '0' || text[i] > '9') return std::nullopt;
    value = value * 10 + static_cast<unsigned>(text[i] - '0');
  }
  return value;
}

// YYYY-MM-DD at the start of `text` as a valid date, or nullopt.
std::optional<UtcDay> leadingDay(std::string_view text) {
  const auto y = fixedDigits(text, 0, 4), m = fixedDigits(text, 5, 2), d = fixedDigits(text, 8, 2);
  if (!y || !m || !d || text[4] != '-' || text[7] != '-') return std::nullopt;
  const year_month_day date{year(static_cast<int>(*y)), month(*m), day(*d)};
  if (!date.ok()) return std::nullopt;
  return UtcDay(date);
}

}  // namespace

Result<UtcDay> parseIsoDay(std::string_view text) {
  const bool shaped = text.size() == 10 && fixedDigits(text, 0, 4) && text[4] == '-' &&
                      fixedDigits(text, 5, 2) && text[7] == '-' && fixedDigits(text, 8, 2);
  if (!shaped) return badInput(fmt::format("\"{}\": expected a date YYYY-MM-DD", text));
  const auto day = leadingDay(text);
  if (!day) return badInput(fmt::format("\"{}\": no such date", text));
  return *day;
}

std::optional<UtcDay> isoDayOf(std::string_view text) {
  if (text.size() > 10 && text[10] != 'T' && text[10] != 't' && text[10] != ' ')
    return std::nullopt;
  return leadingDay(text);
}

int daysInYear(int year) { return std::chrono::year{year}.is_leap() ? 366 : 365; }

int daysInMonth(int year, int month) {
  const std::chrono::year_month_day_last last{std::chrono::year{year} /
                                              std::chrono::month{static_cast<unsigned>(month)} /
                                              std::chrono::last};
  return static_cast<int>(static_cast<unsigned>(last.day()));
}

std::string formatIsoDay(UtcDay day) {
  const year_month_day date{day};
  char text[32];
  const int length =
      std::snprintf(text, sizeof text, "%04d-%02u-%02u", static_cast<int>(date.year()),
                    static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()));
  return std::string(text, static_cast<std::size_t>(length));
}

std::string formatStackStamp(UtcTime utc) {
  const sys_days day = floor<days>(utc);
  const year_month_day date{day};
  const hh_mm_ss<seconds> time{floor<seconds>(utc - day)};
  char text[32];
  const int length = std::snprintf(
      text, sizeof text, "%04d%02u%02uT%02ld%02ld%02lldZ", static_cast<int>(date.year()),
      static_cast<unsigned>(date.month()), static_cast<unsigned>(date.day()),
      static_cast<long>(time.hours().count()), static_cast<long>(time.minutes().count()),
      static_cast<long long>(time.seconds().count()));
  return std::string(text, static_cast<std::size_t>(length));
}

std::optional<std::chrono::sys_seconds> parseStackStamp(std::string_view id) {
  if (id.size() < kStackStampLength || id[8] != 'T' || id[15] != 'Z') return std::nullopt;
  const auto y = fixedDigits(id, 0, 4), m = fixedDigits(id, 4, 2), d = fixedDigits(id, 6, 2);
  const auto hh = fixedDigits(id, 9, 2), mm = fixedDigits(id, 11, 2), ss = fixedDigits(id, 13, 2);
  if (!y || !m || !d || !hh || !mm || !ss) return std::nullopt;
  const year_month_day date{year(static_cast<int>(*y)), month(*m), day(*d)};
  if (!date.ok() || *hh > 23 || *mm > 59 || *ss > 59) return std::nullopt;
  return sys_days(date) + hours(*hh) + minutes(*mm) + seconds(*ss);
}

}  // namespace glarecam
