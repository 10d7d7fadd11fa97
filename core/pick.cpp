#include "core/pick.h"

#include <algorithm>
#include <string>

#include "core/check.h"

namespace tessera {

std::optional<uint32_t> triangle_of_key(uint64_t key) {
  if (key == kEmptyVisibilityKey) return std::nullopt;
  return uint32_t(key & 0xFFFFFFFFu);
}

uint32_t object_of_triangle(const ObjectNumbering& numbering, uint64_t triangle_id) {
  if (triangle_id >= numbering.triangle_count) {
    throw Error("triangle instance " + std::to_string(triangle_id) +
                " is not in the scene (it has " + std::to_string(numbering.triangle_count) +
                "): the key comes from another scene's frame");
  }
  TESSERA_CHECK(numbering.first_triangle.size() == numbering.objects.size());
  // first_triangle is strictly increasing (objects without triangles are not numbered), so
  // the owner is the last object whose first triangle is <= triangle_id.
  const auto it = std::upper_bound(numbering.first_triangle.begin(), numbering.first_triangle.end(),
                                   triangle_id);
  TESSERA_CHECK(it != numbering.first_triangle.begin());
  return numbering.objects[size_t(it - numbering.first_triangle.begin()) - 1];
}

std::optional<uint32_t> pick_object(const ObjectNumbering& numbering, uint64_t key) {
  const std::optional<uint32_t> triangle = triangle_of_key(key);
  if (!triangle) return std::nullopt;
  return object_of_triangle(numbering, *triangle);
}

}  // namespace tessera
