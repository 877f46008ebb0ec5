// glarecamd's log to the systemd journal with structured fields: an spdlog sink that sends each
// message with PRIORITY, SYSLOG_IDENTIFIER and the GLARECAM_* fields of the scope it was logged
// in (ScopedLogFields), so that `journalctl -u glarecamd GLARECAM_STACK=...` finds one stack's
// story and GLARECAM_EVENT=capture every capture. The journal is chosen when systemd connected
// stderr to it ($JOURNAL_STREAM, systemd.exec(5)); a failed send never throws (a log that cannot
// be written must not stop a capture).
#pragma once

#include <spdlog/sinks/sink.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace glarecam::daemon {

// Journal field names: upper-case letters, digits and '_', not starting with '_' or a digit
// (sd_journal_send(3)); values are any text.
using LogFields = std::vector<std::pair<std::string, std::string>>;

// While alive, adds its fields to every message logged on this thread (nested scopes add up).
class ScopedLogFields {
 public:
  explicit ScopedLogFields(LogFields fields);
  ~ScopedLogFields();
  ScopedLogFields(const ScopedLogFields&) = delete;
  ScopedLogFields& operator=(const ScopedLogFields&) = delete;

 private:
  std::size_t previous_size_;
};

// The fields of the scopes alive on this thread, innermost last.
const LogFields& currentLogFields();

// The journal entry's fields for one message ("MESSAGE=...", "PRIORITY=4", ...), invalid field
// names dropped: what the sink sends, pure for tests.
std::vector<std::string> journalEntry(const std::string& identifier, int syslog_priority,
                                      std::string_view message, const LogFields& fields);

std::shared_ptr<spdlog::sinks::sink> makeJournalSink(std::string identifier);

// True when systemd connected stderr to the journal: $JOURNAL_STREAM holds stderr's device and
// inode.
bool stderrIsJournal();

}  // namespace glarecam::daemon
