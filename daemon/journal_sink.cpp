#include "daemon/journal_sink.h"

#include <fmt/format.h>
#include <spdlog/sinks/base_sink.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <syslog.h>
#include <systemd/sd-journal.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <mutex>

namespace glarecam::daemon {

namespace {

thread_local LogFields t_fields;

bool validFieldName(const std::string& name) {
  if (name.empty() || name[0] == '_' || (name[0] >= '0' && name[0] <= '9')) return false;
  for (const char c : name)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

int syslogPriority(spdlog::level::level_enum level) {
  switch (level) {
    case spdlog::level::trace:
    case spdlog::level::debug:
      return LOG_DEBUG;
    case spdlog::level::info:
      return LOG_INFO;
    case spdlog::level::warn:
      return LOG_WARNING;
    case spdlog::level::err:
      return LOG_ERR;
    case spdlog::level::critical:
      return LOG_CRIT;
    default:
      return LOG_INFO;
  }
}

class JournalSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit JournalSink(std::string identifier) : identifier_(std::move(identifier)) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    const std::vector<std::string> entry =
        journalEntry(identifier_, syslogPriority(msg.level),
                     std::string_view(msg.payload.data(), msg.payload.size()), currentLogFields());
    std::vector<iovec> vectors;
    vectors.reserve(entry.size());
    for (const std::string& field : entry)
      vectors.push_back({const_cast<char*>(field.data()), field.size()});
    sd_journal_sendv(vectors.data(), static_cast<int>(vectors.size()));  // failures ignored
  }
  void flush_() override {}

 private:
  std::string identifier_;
};

}  // namespace

ScopedLogFields::ScopedLogFields(LogFields fields) : previous_size_(t_fields.size()) {
  for (auto& field : fields) t_fields.push_back(std::move(field));
}

ScopedLogFields::~ScopedLogFields() { t_fields.resize(previous_size_); }

const LogFields& currentLogFields() { return t_fields; }

std::vector<std::string> journalEntry(const std::string& identifier, int syslog_priority,
                                      std::string_view message, const LogFields& fields) {
  std::vector<std::string> entry{fmt::format("MESSAGE={}", message),
                                 fmt::format("PRIORITY={}", syslog_priority),
                                 fmt::format("SYSLOG_IDENTIFIER={}", identifier)};
  for (const auto& [name, value] : fields)
    if (validFieldName(name)) entry.push_back(name + "=" + value);
  return entry;
}

std::shared_ptr<spdlog::sinks::sink> makeJournalSink(std::string identifier) {
  return std::make_shared<JournalSink>(std::move(identifier));
}

bool stderrIsJournal() {
  const char* stream = std::getenv("JOURNAL_STREAM");
  if (!stream) return false;
  struct stat st {};
  if (fstat(STDERR_FILENO, &st) != 0) return false;
  unsigned long long device = 0, inode = 0;
  if (std::sscanf(stream, "%llu:%llu", &device, &inode) != 2) return false;
  return device == st.st_dev && inode == st.st_ino;
}

}  // namespace glarecam::daemon
