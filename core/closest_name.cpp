#include "core/closest_name.h"

#include <algorithm>
#include <vector>

namespace tessera {

namespace {
char lower(char c) {
  return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c;
}
}  // namespace

size_t edit_distance(std::string_view a, std::string_view b) {
  // One row of the dynamic-programming table at a time.
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min(
          {above + 1, row[j - 1] + 1, diagonal + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

namespace {
template <typename Names>
std::string nearest(std::string_view word, const Names& known) {
  std::string best;
  size_t best_distance = 3;  // more than the 2 edits allowed
  for (const auto& name : known) {
    const std::string_view k(name);
    const size_t d = edit_distance(word, k);
    if (d < best_distance && 3 * d <= std::max(word.size(), k.size())) {
      best = k;
      best_distance = d;
    }
  }
  return best;
}
}  // namespace

std::string closest_name(std::string_view word, std::initializer_list<const char*> known) {
  return nearest(word, known);
}

std::string closest_name(std::string_view word, const std::vector<std::string>& known) {
  return nearest(word, known);
}

}  // namespace tessera
