#pragma once
// File types told by their extension, in any case: files from Windows tools often carry
// upper-case ones ("SKY.HDR"), and a check that took ".GLB" but refused "x.PNG" was a puzzle.

#include <string_view>

namespace tessera {

/// Whether `path` is longer than `extension` (".png", in lower case) and ends in it, letters
/// compared without regard to ASCII case.
inline bool has_extension(std::string_view path, std::string_view extension) {
  if (path.size() <= extension.size()) return false;
  const std::string_view tail = path.substr(path.size() - extension.size());
  for (size_t i = 0; i < tail.size(); ++i) {
    const char c = tail[i] >= 'A' && tail[i] <= 'Z' ? char(tail[i] - 'A' + 'a') : tail[i];
    if (c != extension[i]) return false;
  }
  return true;
}

}  // namespace tessera
