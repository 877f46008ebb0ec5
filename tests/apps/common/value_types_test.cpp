// --help names what each option's value is: the table's name for an option read as text, CLI11's
// own for the typed ones, TEXT for an option the table does not know.
#include "apps/common/value_types.h"

#include <gtest/gtest.h>

#include <string>

namespace glarecam::apps {
namespace {

TEST(ValueTypes, NamesTextOptionsByTheirLongName) {
  CLI::App app{"test"};
  std::string alpha, out, unknown;
  double typed = 0;
  CLI::App* process = app.add_subcommand("process", "");
  CLI::Option* alpha_option = process->add_option("--alpha", alpha, "");
  CLI::Option* out_option = process->add_option("--out", out, "");
  CLI::Option* unknown_option = process->add_option("--frobnicate", unknown, "");
  CLI::Option* typed_option = process->add_option("--threshold", typed, "");
  CLI::Option* custom = process->add_option("--size", out, "")->type_name("PIXELS");
  nameOptionValues(app);
  EXPECT_EQ(alpha_option->get_type_name(), "DEG");
  EXPECT_EQ(out_option->get_type_name(), "PATH");
  EXPECT_EQ(unknown_option->get_type_name(), "TEXT");
  EXPECT_EQ(typed_option->get_type_name(), "FLOAT");  // CLI11's own, from the type
  EXPECT_EQ(custom->get_type_name(), "PIXELS");       // named by the command: kept
  EXPECT_NE(process->help().find("--alpha DEG"), std::string::npos) << process->help();
}

}  // namespace
}  // namespace glarecam::apps
