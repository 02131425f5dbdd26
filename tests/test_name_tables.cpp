// Each enum's names come from one table that to_string and its parse
// function share: every value's name parses back to it, and an unknown name
// is refused listing the known ones in the table's order.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/simulation.h"
#include "support/errors.h"

namespace snh::test {
namespace {

template <typename E, typename Parse>
void expect_round_trip(std::initializer_list<E> values, Parse parse) {
  for (E v : values) EXPECT_EQ(parse(to_string(v)), v) << to_string(v);
}

TEST(NameTables, EveryNameParsesBackToItsValue) {
  expect_round_trip(
      {ProductVariant::cached, ProductVariant::recompute, ProductVariant::element_matrices, ProductVariant::assembled},
      parse_product_variant);
  expect_round_trip({Preconditioner::none, Preconditioner::block_jacobi, Preconditioner::multigrid},
                    parse_preconditioner);
  expect_round_trip({MultigridFineLevel::built, MultigridFineLevel::current}, parse_multigrid_fine_level);
  expect_round_trip({ChebyshevKind::first, ChebyshevKind::fourth, ChebyshevKind::optimized_fourth},
                    parse_chebyshev_kind);
  EXPECT_STREQ(to_string(ElementType::hex8), "hex8");
  EXPECT_STREQ(to_string(ElementType::tet4), "tet4");
  EXPECT_STREQ(to_string(ObstacleType::cylinder), "cylinder");
}

TEST(NameTables, UnknownNamesListTheKnownOnes) {
  EXPECT_EQ(error_of([] { parse_product_variant("dense"); }),
            "product variant: expected cached, recompute, element-matrices or assembled, got 'dense'");
  EXPECT_EQ(error_of([] { parse_preconditioner("ilu"); }),
            "preconditioner: expected none, block-jacobi or multigrid, got 'ilu'");
  EXPECT_EQ(error_of([] { parse_multigrid_fine_level("x"); }),
            "multigrid fine level: expected built or current, got 'x'");
  EXPECT_EQ(error_of([] { parse_chebyshev_kind("third"); }),
            "chebyshev kind: expected first, fourth or optimized-fourth, got 'third'");
}

// Unset options (std::optional) read and print as "automatic".
TEST(NameTables, AutomaticIsUnset) {
  EXPECT_EQ(parse_optional("automatic", parse_product_variant), std::nullopt);
  EXPECT_EQ(parse_optional("cached", parse_product_variant), ProductVariant::cached);
  EXPECT_EQ(parse_optional("automatic", parse_chebyshev_kind), std::nullopt);
  EXPECT_THROW(parse_optional("auto", parse_multigrid_fine_level), Error);
  EXPECT_STREQ(name_or_automatic(std::optional<MultigridFineLevel>()), "automatic");
  EXPECT_STREQ(name_or_automatic(std::optional<MultigridFineLevel>(MultigridFineLevel::built)), "built");
}

}  // namespace
}  // namespace snh::test
