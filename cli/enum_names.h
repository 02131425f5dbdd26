// An enum's names as the library's one name table for it gives them (through
// its to_string), for the command lines: the choices an option accepts and
// the value a name stands for. Adding a value to the library's table adds it
// to every option built from these.
#pragma once

#include <CLI/CLI.hpp>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "snh/device.h"
#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh::cli {

// The names of the values 0, 1, 2, ... up to the first outside the table:
// for a to_string that answers such a value with a word that is no name
// (ElementType's "unknown"), the first whose name is that of a value far
// outside the table.
template <typename E>
std::vector<std::string> enum_names(const char* (*name)(E)) {
  using Underlying = std::underlying_type_t<E>;
  const std::string fallback = name(static_cast<E>(std::numeric_limits<Underlying>::max()));
  std::vector<std::string> out;
  for (Underlying i = 0; name(static_cast<E>(i)) != fallback; ++i) out.push_back(name(static_cast<E>(i)));
  return out;
}

// The same for an enum with a parse function: the values 0, 1, 2, ... up to
// the first whose name does not parse back to it (a to_string may answer
// values outside its table with one of its names).
template <typename E>
std::vector<std::string> enum_names(const char* (*name)(E), E (*parse)(const std::string&)) {
  using Underlying = std::underlying_type_t<E>;
  std::vector<std::string> out;
  for (Underlying i = 0;; ++i) {
    const E value = static_cast<E>(i);
    try {
      if (parse(name(value)) != value) break;
    } catch (const Error&) {
      break;
    }
    out.push_back(name(value));
  }
  return out;
}

// `names` less `drop`, then `extra` (e.g. the preconditioners less
// "automatic", then "both").
inline std::vector<std::string> names_with(std::vector<std::string> names, const std::vector<std::string>& extra,
                                           const std::vector<std::string>& drop = {}) {
  std::vector<std::string> out;
  for (const std::string& n : names) {
    bool dropped = false;
    for (const std::string& d : drop) dropped = dropped || d == n;
    if (!dropped) out.push_back(n);
  }
  out.insert(out.end(), extra.begin(), extra.end());
  return out;
}

// The value named `text`; else snh::Error "<what>: expected a, b or c, got
// '<text>'".
template <typename E>
E enum_value(const char* (*name)(E), const std::string& text, const char* what) {
  const std::vector<std::string> names = enum_names(name);
  std::string known;
  for (size_t i = 0; i < names.size(); ++i) {
    if (text == names[i]) return static_cast<E>(i);
    known += std::string(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  throw Error(std::string(what) + ": expected " + known + ", got '" + text + "'");
}

// The element types ("hex8", "tet4") and the one a name stands for.
inline std::vector<std::string> element_type_names() { return enum_names<ElementType>(to_string); }
inline ElementType element_type_named(const std::string& text) {
  return enum_value<ElementType>(to_string, text, "element type");
}

// The names of the other enums the command lines take.
inline std::vector<std::string> precision_names() { return enum_names<Precision>(to_string, parse_precision); }
inline std::vector<std::string> preconditioner_names() {
  return enum_names<Preconditioner>(to_string, parse_preconditioner);
}
inline std::vector<std::string> product_variant_names() {
  return enum_names<ProductVariant>(to_string, parse_product_variant);
}
inline std::vector<std::string> hessian_mode_names() { return enum_names<HessianMode>(to_string, parse_hessian_mode); }
inline std::vector<std::string> chebyshev_kind_names() {
  return enum_names<ChebyshevKind>(to_string, parse_chebyshev_kind);
}
inline std::vector<std::string> multigrid_fine_level_names() {
  return enum_names<MultigridFineLevel>(to_string, parse_multigrid_fine_level);
}

}  // namespace snh::cli
