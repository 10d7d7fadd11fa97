#pragma once
// "did you mean ...?" for a misspelt name: the known name nearest to it by edit distance.

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace tessera {

/// The number of single-character insertions, deletions and substitutions that turn `a` into
/// `b` (Levenshtein distance), ignoring ASCII case.
size_t edit_distance(std::string_view a, std::string_view b);

/// The name of `known` nearest to `word`, where it is near enough to be a slip rather than
/// another word: at most 2 edits, and at most a third of the longer of the two ("light" gives
/// "lights"; "fov" gives nothing for "position"). The first of equally near ones; "" for none.
std::string closest_name(std::string_view word, std::initializer_list<const char*> known);
std::string closest_name(std::string_view word, const std::vector<std::string>& known);

}  // namespace tessera
