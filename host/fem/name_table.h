// An enum's printable names as one table, read by both directions: to_string
// and its parse function (the pattern of snh/outcomes.h). Internal.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "snh/error.h"

namespace snh {

template <typename E, size_t N>
using NameTable = std::array<std::pair<E, const char*>, N>;

// The value's name; `unknown` for a value the table lacks.
template <typename E, size_t N>
const char* name_of(const NameTable<E, N>& table, E value, const char* unknown = "?") {
  for (const auto& [v, name] : table)
    if (v == value) return name;
  return unknown;
}

// The value named `text`; else snh::Error "<what>: expected a, b or c, got
// '<text>'" with the table's names in its order (an empty name, such as
// StepStatus::none's, parses but is not listed).
template <typename E, size_t N>
E value_named(const NameTable<E, N>& table, const std::string& text, const char* what) {
  std::vector<std::string> names;
  for (const auto& [value, name] : table) {
    if (text == name) return value;
    if (*name != '\0') names.push_back(name);
  }
  std::string known;
  for (size_t i = 0; i < names.size(); ++i) known += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  throw Error(std::string(what) + ": expected " + known + ", got '" + text + "'");
}

}  // namespace snh
