// The command lines' choices come from the library's name tables
// (cli/enum_names.h): the names in the tables' order, each parsing back to
// its value, and an option built from them refusing anything else.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "enum_names.h"
#include "snh/error.h"

namespace snh::test {
namespace {

using Names = std::vector<std::string>;

TEST(CliEnumNames, ElementTypesComeFromTheTable) {
  EXPECT_EQ(cli::element_type_names(), (Names{"hex8", "tet4"}));
  for (const std::string& name : cli::element_type_names())
    EXPECT_STREQ(to_string(cli::element_type_named(name)), name.c_str());
  try {
    cli::element_type_named("hex20");
    FAIL() << "hex20 accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "element type: expected hex8 or tet4, got 'hex20'");
  }
}

TEST(CliEnumNames, OtherEnumsRoundTrip) {
  EXPECT_EQ(cli::precision_names(), (Names{"float", "double"}));
  EXPECT_EQ(cli::preconditioner_names(), (Names{"automatic", "none", "block-jacobi", "multigrid"}));
  EXPECT_EQ(cli::product_variant_names(), (Names{"automatic", "cached", "recompute", "element-matrices", "assembled"}));
  EXPECT_EQ(cli::hessian_mode_names(), (Names{"projected", "adaptive"}));
  EXPECT_EQ(cli::chebyshev_kind_names(), (Names{"automatic", "first", "fourth", "optimized-fourth"}));
  EXPECT_EQ(cli::multigrid_fine_level_names(), (Names{"automatic", "built", "current"}));
  for (const std::string& name : cli::precision_names()) EXPECT_STREQ(to_string(parse_precision(name)), name.c_str());
  for (const std::string& name : cli::preconditioner_names())
    EXPECT_STREQ(name_or_automatic(parse_optional(name, parse_preconditioner)), name.c_str());
}

TEST(CliEnumNames, NamesWithAddsAndDrops) {
  EXPECT_EQ(cli::names_with(cli::preconditioner_names(), {"both", "all"}, {"automatic"}),
            (Names{"none", "block-jacobi", "multigrid", "both", "all"}));
  EXPECT_EQ(cli::names_with({"automatic"}, cli::precision_names()), (Names{"automatic", "float", "double"}));
}

TEST(CliEnumNames, OptionRefusesOtherNames) {
  auto parse = [](const std::string& value) {
    CLI::App app;
    std::string element = "hex8";
    app.add_option("--element", element)->check(CLI::IsMember(cli::element_type_names()));
    app.parse("--element " + value, false);
    return element;
  };
  EXPECT_EQ(parse("tet4"), "tet4");
  EXPECT_THROW(parse("hex20"), CLI::ValidationError);
}

}  // namespace
}  // namespace snh::test
