#pragma once
// The keys a scene file may hold, object by object: the one list that the reader checks every
// key against (JsonFields refuses to read a key that is not here) and that scene_keys() lists
// for the scene reference (docs/scenes.md, checked against it by a test).

#include <span>
#include <string>
#include <string_view>

namespace deformcd::scene_detail {

/// The keys accepted in the object at `path`: "" for the root, then dotted object names with
/// "[]" for an element of an array ("settings", "bodies[]", "bodies[].material", ...). Throws
/// std::logic_error for a path the table does not have (a reader bug).
[[nodiscard]] std::span<const std::string> keys_at(std::string_view path);

}  // namespace deformcd::scene_detail
