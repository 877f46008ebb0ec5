// Logging to the journal: entries carry the scopes' fields, invalid names are dropped, and
// without a journal nothing fails.
#include "daemon/journal_sink.h"

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace glarecam::daemon {
namespace {

TEST(JournalSink, EntriesCarryTheScopesFieldsAndDropInvalidNames) {
  {
    const ScopedLogFields outer(LogFields{{"GLARECAM_EVENT", "capture"}});
    const ScopedLogFields inner(
        LogFields{{"GLARECAM_STACK", "20260621T101503Z-a42.30"}, {"_PID", "1"}, {"lower", "x"}});
    EXPECT_EQ(journalEntry("glarecamd", 4, "disk: full", currentLogFields()),
              (std::vector<std::string>{"MESSAGE=disk: full", "PRIORITY=4",
                                        "SYSLOG_IDENTIFIER=glarecamd", "GLARECAM_EVENT=capture",
                                        "GLARECAM_STACK=20260621T101503Z-a42.30"}));
  }
  EXPECT_TRUE(currentLogFields().empty());  // the scopes are gone
  // Not connected to the journal here: stderr is a terminal or a file, not $JOURNAL_STREAM's.
  ::setenv("JOURNAL_STREAM", "1:1", 1);
  EXPECT_FALSE(stderrIsJournal());
  ::unsetenv("JOURNAL_STREAM");
  EXPECT_FALSE(stderrIsJournal());
  // Without a journal to send to, logging through the sink must not throw or stop anything.
  auto logger = std::make_shared<spdlog::logger>("journal-test", makeJournalSink("glarecamd"));
  EXPECT_NO_THROW(logger->error("no journald here"));
}

}  // namespace
}  // namespace glarecam::daemon
