// An enum's printable names as one table, read by both directions: to_string
// and its parse function (the pattern of snh/outcomes.h). Internal.
#pragma once

#include <array>
#include <string>
#include <utility>

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
// '<text>'" with the table's names in its order.
template <typename E, size_t N>
E value_named(const NameTable<E, N>& table, const std::string& text, const char* what) {
  std::string known;
  for (size_t i = 0; i < N; ++i) {
    if (text == table[i].second) return table[i].first;
    known += std::string(i == 0 ? "" : i + 1 == N ? " or " : ", ") + table[i].second;
  }
  throw Error(std::string(what) + ": expected " + known + ", got '" + text + "'");
}

}  // namespace snh
