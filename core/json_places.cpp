#include "core/json_places.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <unordered_set>
#include <vector>

#include "core/check.h"

namespace tessera {
namespace {

struct Scanner {
  std::string_view text;
  size_t max_depth;
  size_t pos = 0;
  JsonPlaces out;
  std::vector<size_t> line_starts;  // offset of each line's first byte: places in O(log n)

  JsonPlace place(size_t at) const {
    const auto line = std::upper_bound(line_starts.begin(), line_starts.end(), at);
    return {size_t(line - line_starts.begin()), at - line[-1] + 1};
  }

  [[noreturn]] void fail(size_t at, const std::string& what) const {
    const JsonPlace p = place(at);
    throw Error(std::to_string(p.line) + ":" + std::to_string(p.column) + ": " + what);
  }
  char peek() const { return pos < text.size() ? text[pos] : '\0'; }
  void skip_space() {
    while (pos < text.size() &&
           (text[pos] == ' ' || text[pos] == '\t' || text[pos] == '\n' || text[pos] == '\r'))
      ++pos;
  }
  static void append_utf8(std::string& s, uint32_t c) {
    if (c < 0x80) {
      s += char(c);
    } else if (c < 0x800) {
      s += char(0xC0 | (c >> 6));
      s += char(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      s += char(0xE0 | (c >> 12));
      s += char(0x80 | ((c >> 6) & 0x3F));
      s += char(0x80 | (c & 0x3F));
    } else {
      s += char(0xF0 | (c >> 18));
      s += char(0x80 | ((c >> 12) & 0x3F));
      s += char(0x80 | ((c >> 6) & 0x3F));
      s += char(0x80 | (c & 0x3F));
    }
  }
  uint32_t hex4() {
    const std::string digits(text.substr(pos, 4));
    pos += 4;
    return uint32_t(std::strtoul(digits.c_str(), nullptr, 16));
  }
  // The decoded string at pos (the parser has checked its syntax).
  std::string string() {
    std::string s;
    ++pos;  // opening quote
    while (pos < text.size() && text[pos] != '"') {
      if (text[pos] != '\\') {
        s += text[pos++];
        continue;
      }
      const char e = text[pos + 1];
      pos += 2;
      switch (e) {
        case 'b':
          s += '\b';
          break;
        case 'f':
          s += '\f';
          break;
        case 'n':
          s += '\n';
          break;
        case 'r':
          s += '\r';
          break;
        case 't':
          s += '\t';
          break;
        case 'u': {
          uint32_t c = hex4();
          if (c >= 0xD800 && c < 0xDC00 && text.substr(pos, 2) == "\\u") {
            pos += 2;
            c = 0x10000 + ((c - 0xD800) << 10) + (hex4() - 0xDC00);
          }
          append_utf8(s, c);
          break;
        }
        default:
          s += e;  // " \ /
      }
    }
    ++pos;  // closing quote
    return s;
  }
  void value(const std::string& pointer, size_t depth) {
    skip_space();
    if (depth > max_depth) fail(pos, "nested deeper than " + std::to_string(max_depth) + " levels");
    out.values[pointer] = place(pos);
    const char c = peek();
    if (c == '{') {
      ++pos;
      std::unordered_set<std::string> seen;
      skip_space();
      while (peek() != '}' && pos < text.size()) {
        const size_t key_at = pos;
        const std::string key = string();
        if (!seen.insert(key).second) throw JsonDuplicateKey(place(key_at), pointer, key);
        const std::string child = pointer + "/" + json_pointer_token(key);
        out.keys[child] = place(key_at);
        skip_space();
        ++pos;  // ':'
        value(child, depth + 1);
        skip_space();
        if (peek() == ',') ++pos;
        skip_space();
      }
      ++pos;
    } else if (c == '[') {
      ++pos;
      skip_space();
      for (size_t i = 0; peek() != ']' && pos < text.size(); ++i) {
        value(pointer + "/" + std::to_string(i), depth + 1);
        skip_space();
        if (peek() == ',') ++pos;
        skip_space();
      }
      ++pos;
    } else if (c == '"') {
      string();
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const size_t start = pos;
      while (pos < text.size() &&
             std::string_view("+-.eE0123456789").find(text[pos]) != std::string_view::npos)
        ++pos;
      const std::string number(text.substr(start, pos - start));
      if (!std::isfinite(std::strtod(number.c_str(), nullptr))) {
        throw JsonNumberOverflow(
            place(start), pointer, start, pos - start,
            number + " is out of the range of a number (NaN and infinity are refused)");
      }
    } else {
      while (pos < text.size() && std::isalpha(static_cast<unsigned char>(text[pos]))) ++pos;
    }
  }
};

}  // namespace

JsonPlace place_of_offset(std::string_view text, size_t offset) {
  JsonPlace p{1, 1};
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++p.line;
      p.column = 1;
    } else {
      ++p.column;
    }
  }
  return p;
}

std::string json_pointer_token(std::string_view token) {
  std::string s;
  for (char c : token) {
    if (c == '~')
      s += "~0";
    else if (c == '/')
      s += "~1";
    else
      s += c;
  }
  return s;
}

JsonPlaces index_json_places(std::string_view text, size_t max_depth) {
  Scanner scanner{text, max_depth};
  scanner.line_starts.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') scanner.line_starts.push_back(i + 1);
  scanner.value("", 0);
  return std::move(scanner.out);
}

}  // namespace tessera
