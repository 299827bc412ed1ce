// The registry: unique names, lookups, and the checks of what a format needs
// before its writer or reader runs.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/export.h"

namespace mpcal {
namespace {

TEST(ExportRegistry, NamesAreUniqueLowerCaseAndFound) {
  std::set<std::string> names;
  for (const ExportFormat& f : ExportFormats()) {
    const std::string name(f.name);
    EXPECT_TRUE(names.insert(name).second) << name;
    for (char c : name)
      EXPECT_TRUE((c >= 'a' && c <= 'z') || c == '-' || (c >= '0' && c <= '9')) << name;
    EXPECT_FALSE(f.file.empty()) << name;
    EXPECT_TRUE(f.write != nullptr || f.read != nullptr) << name;
    if (f.read != nullptr) {
      EXPECT_GE(f.min_files, 1) << name;
      EXPECT_GE(f.max_files, f.min_files) << name;
      EXPECT_FALSE(f.import_files.empty()) << name;
    }
    EXPECT_EQ(FindExportFormat(name), &f);
  }
  EXPECT_EQ(FindExportFormat("no-such-format"), nullptr);
}

TEST(ExportRegistry, AFileTheFormatRequiresMustBeGiven) {
  const ExportFormat* kalibr = FindExportFormat("kalibr");
  ASSERT_NE(kalibr, nullptr);
  ASSERT_EQ(kalibr->noise, ExportNeed::kRequired);
  EXPECT_THROW(Export(*kalibr, ExportSources{}, ExportOptions{}), Error);
}

TEST(ExportRegistry, AnExportOnlyFormatIsNotRead) {
  for (const ExportFormat& f : ExportFormats()) {
    if (f.read != nullptr) continue;
    EXPECT_THROW(Import(f, {ImportFile{"x", ""}}, ImportOptions{}), Error) << f.name;
  }
}

}  // namespace
}  // namespace mpcal
