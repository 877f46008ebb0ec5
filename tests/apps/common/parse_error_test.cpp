// The one-line message for a command line CLI11 refused, on a small app shaped like glarecam's:
// misspelt commands and options get the closest known name, a flag given a value is refused as
// such, and other errors keep CLI11's message.
#include "apps/common/parse_error.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace glarecam::apps {
namespace {

// Parses `words` (after the program name) on an app with a `process` command and a `calibrate`
// command holding `dark`; returns the message, or "" when the parse succeeded.
std::string messageFor(std::vector<std::string> words) {
  CLI::App app{"test"};
  app.option_defaults()->disable_flag_override();
  app.require_subcommand(1);
  app.fallthrough();
  bool quiet = false, json = false;
  std::string out;
  double threshold = 0;
  app.add_flag("-q,--quiet", quiet, "");
  CLI::App* process = app.add_subcommand("process", "");
  process->add_option("--out", out, "");
  process->add_option("--threshold", threshold, "");
  process->add_flag("--json", json, "");
  CLI::App* calibrate = app.add_subcommand("calibrate", "");
  calibrate->require_subcommand(1);
  calibrate->add_subcommand("dark", "");
  words.insert(words.begin(), "glarecam");
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    return parseErrorMessage(app, e, static_cast<int>(argv.size()), argv.data());
  }
  return "";
}

TEST(ParseError, NamesTheClosestCommand) {
  EXPECT_EQ(messageFor({"procss"}),
            "unknown command \"procss\" (did you mean process?) (known: process, calibrate)");
  EXPECT_EQ(messageFor({"calibrate", "drak"}),
            "calibrate: unknown command \"drak\" (did you mean dark?) (known: dark)");
  EXPECT_EQ(messageFor({"frobnicate"}),
            "unknown command \"frobnicate\" (known: process, calibrate)");
}

TEST(ParseError, NamesTheClosestOption) {
  EXPECT_EQ(messageFor({"process", "--threshhold", "3e4"}),
            "process: unknown option --threshhold (did you mean --threshold?)");
  EXPECT_EQ(messageFor({"process", "--output=x"}),
            "process: unknown option --output (did you mean --out?)");
  EXPECT_EQ(messageFor({"process", "--zzz"}), "process: unknown option --zzz");
  // A negative number is a value, not an option; the option before it is the unknown one.
  EXPECT_EQ(messageFor({"process", "--treshold", "-5"}),
            "process: unknown option --treshold (did you mean --threshold?)");
}

// The value after an unknown option is not taken for a command; short flags may be combined;
// nothing after "--" is an option or a command.
TEST(ParseError, TheUnknownOptionIsNamedNotItsValue) {
  EXPECT_EQ(messageFor({"calibrate", "--bogus", "3", "dark"}),
            "calibrate dark: unknown option --bogus");
  EXPECT_EQ(messageFor({"process", "-qq", "--zzz"}), "process: unknown option --zzz");
}

TEST(ParseError, RefusesAValueGivenToAFlag) {
  EXPECT_EQ(messageFor({"process", "--json=yes"}),
            "process: --json is a flag and takes no value (got \"yes\"): give --json alone");
  EXPECT_EQ(messageFor({"--quiet=false", "process"}),
            "--quiet is a flag and takes no value (got \"false\"): give --quiet alone");
  EXPECT_EQ(messageFor({"process", "--json", "--quiet"}), "");  // flags alone parse
}

TEST(ParseError, OtherErrorsKeepCli11sMessage) {
  const std::string message = messageFor({"process", "--threshold", "abc"});
  EXPECT_NE(message.find("--threshold"), std::string::npos) << message;
  EXPECT_EQ(message.find("did you mean"), std::string::npos) << message;
  EXPECT_EQ(message.find("unknown"), std::string::npos) << message;
}

}  // namespace
}  // namespace glarecam::apps
