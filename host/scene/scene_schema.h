// The keys a scene file accepts, in one table: each object of the format by
// its path from the root ("" the root, "[]" an array's elements, e.g.
// "constraints[].motion.keys[]") with its keys. The loader rejects keys an
// object's entry does not list; scene_file_keys() lists them all.
#pragma once

#include <set>
#include <string>

namespace snh::scene_io {

// The keys of the object at `schema_path`; `variant` picks one of an object's
// forms where they take different keys (an obstacle's "type"). Throws
// std::logic_error for a path the table lacks (a loader bug).
const std::set<std::string>& allowed_keys(const std::string& schema_path, const std::string& variant = "");

// A key path with its array indices dropped: "constraints[2].motion.keys[0]"
// -> "constraints[].motion.keys[]"; "scene" (the root in messages) -> "".
std::string schema_path(const std::string& key_path);

}  // namespace snh::scene_io
