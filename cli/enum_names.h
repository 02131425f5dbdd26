// An enum's names as the library's one name table for it gives them (through
// its to_string), for the command lines: the choices an option accepts and
// the value a name stands for. Adding a value to the library's table adds it
// to every option built from these.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "snh/device.h"
#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/simulation.h"

namespace snh::cli {

// The names of an enum's values 0, 1, 2, ... up to the first whose name
// does not parse back to it (a to_string may answer values outside its
// table with one of its names, or with a word that is no name).
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

// The element types ("hex8", "tet4") and the one a name stands for.
inline std::vector<std::string> element_type_names() {
  return enum_names<ElementType>(element_type_name, parse_element_type);
}
inline ElementType element_type_named(const std::string& text) { return parse_element_type(text); }

// The names of the other enums the command lines take. Options that are
// std::optional in the library take "automatic" first, for unset (read
// with snh::parse_optional).
inline std::vector<std::string> precision_names() { return enum_names<Precision>(to_string, parse_precision); }
inline std::vector<std::string> preconditioner_names() {
  return names_with({kAutomatic}, enum_names<Preconditioner>(to_string, parse_preconditioner));
}
inline std::vector<std::string> product_variant_names() {
  return names_with({kAutomatic}, enum_names<ProductVariant>(to_string, parse_product_variant));
}
inline std::vector<std::string> hessian_mode_names() { return enum_names<HessianMode>(to_string, parse_hessian_mode); }
inline std::vector<std::string> chebyshev_kind_names() {
  return names_with({kAutomatic}, enum_names<ChebyshevKind>(to_string, parse_chebyshev_kind));
}
inline std::vector<std::string> multigrid_fine_level_names() {
  return names_with({kAutomatic}, enum_names<MultigridFineLevel>(to_string, parse_multigrid_fine_level));
}

}  // namespace snh::cli
