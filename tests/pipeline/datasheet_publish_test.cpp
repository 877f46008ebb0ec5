// Publishing a sweep: the warning when --module disagrees with the module the stacks name.
#include "pipeline/datasheet_publish.h"

#include <gtest/gtest.h>

#include <string>

#include "pipeline/sweep_table.h"

namespace glarecam::pipeline {
namespace {

SweepTable tableOfModules(std::initializer_list<const char*> modules) {
  SweepTable table;
  for (const char* module : modules) {
    SweepRow row;
    row.module = module;
    table.rows.push_back(row);
  }
  return table;
}

TEST(ModuleMismatch, AModuleTheStacksDoNotNameIsWarnedAbout) {
  const SweepTable table = tableOfModules({"PV-A 400", "PV-A 400", "PV-B 410"});
  EXPECT_EQ(moduleMismatch("PV-C", table),
            "--module \"PV-C\" is not the module the stacks were recorded of (\"PV-A 400\", "
            "\"PV-B 410\"); the sheet says \"PV-C\"");
  EXPECT_FALSE(moduleMismatch("PV-B 410", table));  // one of the stacks' modules
}

TEST(ModuleMismatch, NothingToSayWithoutAModuleOnEitherSide) {
  EXPECT_FALSE(moduleMismatch("PV-C", tableOfModules({"", ""})));  // the stacks name none
  EXPECT_FALSE(moduleMismatch(SweepPublishOptions{}.module, tableOfModules({"PV-A 400"})));
}

}  // namespace
}  // namespace glarecam::pipeline
