#pragma once
// Where each value of a JSON text is: nlohmann-json parses without keeping positions, so a
// second pass over the (already parsed) text maps each value's JSON pointer to its line and
// column, for messages that point into the file.

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "core/check.h"

namespace tessera {

/// 1-based line and column (in bytes) of a place in a text; 0:0 when unknown.
struct JsonPlace {
  size_t line = 0, column = 0;
};

/// Line and column of byte `offset` (0-based) of `text`.
JsonPlace place_of_offset(std::string_view text, size_t offset);

struct JsonPlaces {
  /// Keyed by RFC 6901 JSON pointer ("" is the root, "/materials/0/roughness").
  std::unordered_map<std::string, JsonPlace> values;  // where each value starts
  std::unordered_map<std::string, JsonPlace> keys;    // where each object member's key starts
};

/// What index_json_places throws for a number that overflows a double: its message is
/// "LINE:COLUMN: what", and it says which value that is, for a caller that names the value by
/// its path (nlohmann-json stops at such a number, so the caller has no document to walk).
struct JsonNumberOverflow : Error {
  JsonNumberOverflow(JsonPlace place, std::string pointer, size_t offset, size_t length,
                     std::string what)
      : Error(std::to_string(place.line) + ":" + std::to_string(place.column) + ": " + what),
        place(place),
        pointer(std::move(pointer)),
        offset(offset),
        length(length),
        reason(std::move(what)) {}
  JsonPlace place;
  std::string pointer;  // the number's RFC 6901 JSON pointer
  size_t offset = 0;    // its first byte in the text
  size_t length = 0;    // and its length in bytes
  std::string reason;   // the message without the place
};

/// What index_json_places throws for a key given twice in one object: "LINE:COLUMN: key 'K'
/// is given twice", with the object's JSON pointer and the key, for a caller that names the
/// value by its path (materials.gold.roughness).
struct JsonDuplicateKey : Error {
  JsonDuplicateKey(JsonPlace place, std::string object, std::string key)
      : Error(std::to_string(place.line) + ":" + std::to_string(place.column) + ": key '" + key +
              "' is given twice"),
        place(place),
        object(std::move(object)),
        key(std::move(key)) {}
  JsonPlace place;     // where the second one is
  std::string object;  // the RFC 6901 JSON pointer of the object that has it twice
  std::string key;
};

/// Indexes every value of `text`, which nlohmann-json has parsed (or refused only for a number
/// out of double's range). Throws Error("LINE:COLUMN: ...") for what the parser lets through
/// but a scene file must not have: a number that overflows a double (1e999, as
/// JsonNumberOverflow), a key given twice in one object (as JsonDuplicateKey), nesting deeper than
/// `max_depth`.
JsonPlaces index_json_places(std::string_view text, size_t max_depth = 64);

/// `token` escaped for use in a JSON pointer (~ as ~0, / as ~1).
std::string json_pointer_token(std::string_view token);

}  // namespace tessera
