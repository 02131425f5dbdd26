// Element type names come from one table (snh/mesh.h): every type's name
// parses back to it, to_string is that name, an unknown name is refused
// naming it and the valid ones, and the command lines and the scene files
// take the same names.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "enum_names.h"
#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/outcomes.h"
#include "snh/scene.h"
#include "support/errors.h"

namespace snh::test {
namespace {

TEST(ElementTypeNames, EveryTypeRoundTrips) {
  for (ElementType type : {ElementType::hex8, ElementType::tet4}) {
    EXPECT_EQ(parse_element_type(element_type_name(type)), type) << element_type_name(type);
    EXPECT_STREQ(to_string(type), element_type_name(type));
  }
  EXPECT_STREQ(element_type_name(ElementType::hex8), "hex8");
  EXPECT_STREQ(element_type_name(ElementType::tet4), "tet4");
  EXPECT_EQ(cli::element_type_names(), (std::vector<std::string>{"hex8", "tet4"}));
}

TEST(ElementTypeNames, UnknownNameIsNamedWithTheValidOnes) {
  EXPECT_EQ(error_of([] { parse_element_type("hex20"); }), "element type: expected hex8 or tet4, got 'hex20'");
  EXPECT_EQ(error_of([] { parse_element_type(""); }), "element type: expected hex8 or tet4, got ''");
  EXPECT_EQ(error_of([] { parse_element_type("HEX8"); }), "element type: expected hex8 or tet4, got 'HEX8'");
}

// A scene file's mesh.element: parsed by the same table, a hex8 lattice
// kept or split into tet4, an unknown name refused under its key.
TEST(ElementTypeNames, SceneFileElementKeyUsesTheTable) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "snh_element_type_names.json";
  auto load = [&](const std::string& element) {
    std::ofstream(path) << R"({"mesh": {"generator": "box", "cells": [1, 1, 1], "size": 0.5, "element": ")" + element +
                               R"("}})";
    return load_scene(path.string());
  };
  EXPECT_EQ(load("hex8").scene.mesh.type, ElementType::hex8);
  EXPECT_EQ(load("tet4").scene.mesh.type, ElementType::tet4);
  const std::string bad = error_of([&] { load("hex20"); });
  EXPECT_TRUE(contains(bad, "mesh.element: element type: expected hex8 or tet4, got 'hex20'")) << bad;
  std::filesystem::remove(path);
}

// The outcomes' tables (snh/outcomes.h) refuse a name as the other enums do,
// listing the names (not StepStatus::none's empty one).
TEST(NameTables, OutcomesListTheKnownNamesLikeTheOtherEnums) {
  EXPECT_EQ(error_of([] { parse_cg_stop("diverged"); }),
            "CG stop: expected converged, max_iterations, negative_curvature or breakdown, got 'diverged'");
  EXPECT_EQ(error_of([] { parse_step_status("converge"); }),
            "step status: expected converged, max_newton_iterations, line_search_failed, stagnated, "
            "non_finite_state, cancelled or inverted_elements, got 'converge'");
  EXPECT_EQ(parse_step_status(""), StepStatus::none);
  EXPECT_EQ(parse_cg_stop(""), CgStop::none);
}

}  // namespace
}  // namespace snh::test
