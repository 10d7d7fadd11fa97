// Wavefront OBJ/MTL import (core/model_import.h). tinyobjloader parses, through its streaming
// API (LoadObjWithCallback), whose callbacks build Tessera's meshes as faces are read, so no
// parser arrays exist beside them; this file checks what tinyobjloader does not (it drops bad
// faces and clamps nothing, reporting out-of-range indices once per file without the line) by
// scanning each line just before tinyobjloader reads it (MTL files: each file first), so every
// error names its line and column. The scan also gives the callbacks what they do not report:
// smoothing groups (`s`) and the lines of polygons, for warnings.
//
// Conventions chosen here, each because the format leaves it open:
// - Polygons are split by this file, not by tinyobjloader: convex ones as a fan from their first
//   corner (quads: (0 1 2) (0 2 3)), concave ones by ear clipping in the plane of their Newell
//   normal. tinyobjloader's built-in splitter picks quad diagonals by length and can lose
//   polygons it fails to clip; here every polygon of n corners gives n - 2 triangles.
// - Missing normals follow OBJ smoothing groups, as the format defines them: faces in group
//   `s k` (k > 0) share area-weighted vertex normals with the faces of group k that touch the
//   same position; faces with `s off` (the default) are flat.
// - OBJ puts v = 0 at the bottom of an image; Tessera's v = 0 is the top row (core/texture.h),
//   so v becomes 1 - v.
// - A face has at most 255 corners: tinyobjloader counts them in an unsigned char, so a longer
//   one is an error naming its line (it would be cut silently).
// - `usemtl` names the material of the whole rest of its line where a library declares one of
//   that name (`newmtl` names run to the end of the line: "newmtl My Red"), else of its first
//   word, as LoadObj reads it; a name no library declares is warned about once.
// - `Ns` (a Blinn-Phong exponent) becomes roughness by matching Beckmann's alpha, alpha^2 =
//   2 / (Ns + 2) (Walter et al. 2007, "Microfacet Models for Refraction through Rough
//   Surfaces", section 5.2), taken as GGX alpha = roughness^2. `Pr` overrides it.
// - Vertex colours (`v x y z r g b`, an extension some exporters write) are not read: materials
//   have no vertex-colour input. They are warned about once, with their count.
// - The text is ASCII or UTF-8, as OBJ and MTL files are written: a UTF-16 file (one that starts
//   with the byte-order mark FF FE or FE FF, or has a NUL byte) is an error at that place, where
//   every one of its lines would otherwise be ignored and the file said to have no faces (or
//   no materials).

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include <stb/stb_image.h>
#include <tiny_obj_loader.h>

#include "core/check.h"
#include "core/mapped_file.h"
#include "core/model_import.h"
#include "core/parallel.h"
#include "core/texture.h"

namespace tessera {

namespace {

namespace fs = std::filesystem;

std::string quoted(const std::string& path) {
  return "'" + path + "'";
}

std::string place(const std::string& file, size_t line, size_t column = 0) {
  std::string s = quoted(file) + " line " + std::to_string(line);
  if (column > 0) s += ", column " + std::to_string(column);
  return s;
}

[[noreturn]] void fail(const std::string& file, size_t line, size_t column,
                       const std::string& what) {
  throw Error(place(file, line, column) + ": " + what);
}

void check_size(const std::string& path, uint64_t size, uint64_t max_bytes) {
  if (size > max_bytes) {
    throw Error(quoted(path) + " is " + std::to_string(size) + " bytes, over the limit of " +
                std::to_string(max_bytes) + " (ImportOptions::max_file_bytes)");
  }
}

/// Reads a whole file, refusing one over `max_bytes`. Returns nullopt if it does not exist.
std::optional<std::string> read_limited(const std::string& path, uint64_t max_bytes) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  const uint64_t size = fs::file_size(path, ec);
  if (ec) throw Error("cannot read " + quoted(path) + ": " + ec.message());
  check_size(path, size, max_bytes);
  std::ifstream in(path, std::ios::binary);
  std::string text(size, '\0');
  if (!in.read(text.data(), std::streamsize(size))) throw Error("cannot read " + quoted(path));
  return text;
}

struct Token {
  std::string_view text;
  size_t column = 0;  // 1-based
};

/// The whitespace-separated words of one line, with their columns.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : line_(line) {}
  std::optional<Token> next() {
    while (pos_ < line_.size() && (line_[pos_] == ' ' || line_[pos_] == '\t')) ++pos_;
    if (pos_ >= line_.size()) return std::nullopt;
    const size_t start = pos_;
    while (pos_ < line_.size() && line_[pos_] != ' ' && line_[pos_] != '\t') ++pos_;
    return Token{line_.substr(start, pos_ - start), start + 1};
  }
  /// What is left of the line, without the spaces and tabs around it.
  std::string_view rest() const {
    const size_t start = std::min(line_.find_first_not_of(" \t", pos_), line_.size());
    const size_t end = line_.find_last_not_of(" \t");
    return end == std::string_view::npos || end < start ? std::string_view()
                                                        : line_.substr(start, end + 1 - start);
  }

 private:
  std::string_view line_;
  size_t pos_ = 0;
};

/// The material a `usemtl` line's `rest` names among `materials` (a map or a set of names): the
/// whole rest of the line where a material has that name (`newmtl` names run to the end of
/// their line, so they may hold spaces: "usemtl My Red"), else its first word, as LoadObj reads
/// it.
template <typename Names>
std::string material_name(std::string_view rest, const Names& materials) {
  const size_t start = std::min(rest.find_first_not_of(" \t"), rest.size());
  const size_t end = rest.find_last_not_of(" \t\r");
  const std::string whole(end == std::string_view::npos || end < start
                              ? std::string_view()
                              : rest.substr(start, end + 1 - start));
  if (materials.count(whole)) return whole;
  return std::string(rest.substr(start, rest.find_first_of(" \t\r", start) - start));
}

/// Calls f(line_number, line) for each complete line of `text`, numbering on from `line`, and
/// returns how many bytes those lines took. Lines end as tinyobjloader ends them (its
/// safeGetline): at "\n", "\r\n" or a lone "\r"; otherwise the scan and tinyobjloader would see
/// different statements (a "\rv" line is a vertex to tinyobjloader; found by fuzzing). Unless
/// `last`, an unterminated final line, or one ending in a final "\r" (the start of "\r\n"?),
/// waits for more text.
template <typename F>
size_t split_lines(std::string_view text, bool last, size_t& line, F&& f) {
  const char* const data = text.data();
  const size_t size = text.size();
  // memchr for each terminator (a search for either byte is a loop per byte); where the next
  // '\r' is is kept, since most files have none.
  const char* cr = static_cast<const char*>(std::memchr(data, '\r', size));
  size_t start = 0;
  while (start < size) {
    if (cr && cr < data + start)
      cr = static_cast<const char*>(std::memchr(data + start, '\r', size - start));
    const char* lf = static_cast<const char*>(std::memchr(data + start, '\n', size - start));
    const char* eol = lf && (!cr || lf < cr) ? lf : cr;
    if (!eol) {
      if (!last) break;
      f(++line, text.substr(start));
      return size;
    }
    const size_t end = size_t(eol - data);
    if (*eol == '\r' && end + 1 == size && !last) break;
    f(++line, text.substr(start, end - start));
    start = end + (*eol == '\r' && end + 1 < size && data[end + 1] == '\n' ? 2 : 1);
  }
  return start;
}

template <typename F>
void for_each_line(std::string_view text, F&& f) {
  size_t line = 0;
  split_lines(text, /*last=*/true, line, f);
}

/// True if `s` is [+-]digits[.digits] with 1 to 15 integer digits (or none before a fraction)
/// and at least one digit: a number from_chars accepts, finite and within float range, so the
/// full parse can be skipped. Almost every number of an exported OBJ is one. `zero`: all its
/// digits are 0.
bool simple_decimal(std::string_view s, bool& zero) {
  size_t i = s.size() > 0 && (s[0] == '-' || s[0] == '+') ? 1 : 0;
  size_t integer = 0, digits = 0;
  zero = true;
  for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i, ++integer) zero &= s[i] == '0';
  if (integer > 15) return false;
  digits = integer;
  if (i < s.size() && s[i] == '.') {
    for (++i; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i, ++digits) zero &= s[i] == '0';
  }
  return i == s.size() && digits > 0;
}

/// A finite number that fits a float (tinyobjloader stores floats), or an Error at its place.
float parse_number(const std::string& file, size_t line, const Token& t) {
  std::string_view s = t.text;
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec == std::errc::result_out_of_range) {
    fail(file, line, t.column, "'" + std::string(t.text) + "' is out of range");
  }
  if (ec != std::errc() || end != s.data() + s.size()) {
    fail(file, line, t.column, "'" + std::string(t.text) + "' is not a number");
  }
  if (!std::isfinite(value)) {
    fail(file, line, t.column, "'" + std::string(t.text) + "' is not a finite number");
  }
  // Magnitudes below the float range become 0, as they would in any float parser.
  if (std::abs(value) > double(std::numeric_limits<float>::max())) {
    fail(file, line, t.column, "'" + std::string(t.text) + "' is too large for a float");
  }
  return float(value);
}

// ---------------------------------------------------------------------------------------------
// OBJ scan: every check tinyobjloader does not make with a line number.

enum Attribute { kPosition = 0, kTexcoord = 1, kNormal = 2 };
const char* const kAttributeName[3] = {"vertex", "texture coordinate", "normal"};
const char* const kAttributePlural[3] = {"vertices", "texture coordinates", "normals"};

struct ObjScan {
  int64_t count[3] = {0, 0, 0};
  // The largest positive index of each kind and where it is: checked against the file's final
  // counts, since OBJ readers accept references to vertices defined further down.
  int64_t largest[3] = {0, 0, 0};
  size_t largest_line[3] = {0, 0, 0}, largest_column[3] = {0, 0, 0};
  // What the conversion (ObjBuilder) needs from lines tinyobjloader's callbacks do not report,
  // queued in file order: the scan runs at most a chunk ahead of tinyobjloader, and each entry
  // is taken off by the face it belongs to, so the queues stay short.
  std::deque<size_t> polygon_lines;  // line of each face with more than 3 corners
  // `s` statements: (faces before it, smoothing group it sets), read as tinyobjloader's LoadObj
  // reads them.
  std::deque<std::pair<uint64_t, uint32_t>> smoothing;
  std::vector<std::pair<size_t, std::string>> usemtl;  // line, material name
  std::map<std::string, size_t> mtllib_line;           // library name -> line naming it
  uint64_t faces = 0;
  uint64_t zero_normals = 0;  // `vn 0 0 0` (exporters write them for degenerate faces)
  size_t first_zero_normal_line = 0;
  uint64_t coloured_vertices = 0;  // `v x y z r g b`: the colours are not read
  size_t first_coloured_line = 0;
  std::map<std::string, size_t> ignored;  // unsupported keyword -> first line
};

/// One corner of `f`: v, v/vt, v//vn or v/vt/vn (1-based, or negative: relative to the end).
void scan_corner(const std::string& file, size_t line, const Token& t, ObjScan& scan) {
  std::string_view rest = t.text;
  for (int k = 0; k < 3 && !rest.empty(); ++k) {
    const size_t slash = rest.find('/');
    // tinyobjloader reads past a final '/' (into the next corner's number, or "" as index 0
    // and then a normal that does not exist; found by fuzzing).
    if (slash != std::string_view::npos && slash + 1 == rest.size()) {
      fail(file, line, t.column, "'" + std::string(t.text) + "' ends with '/', without an index");
    }
    const std::string_view part = rest.substr(0, slash);
    const size_t column = t.column + size_t(part.data() - t.text.data());
    rest = slash == std::string_view::npos ? std::string_view() : rest.substr(slash + 1);
    if (slash != std::string_view::npos && k == 2) {
      fail(file, line, t.column, "'" + std::string(t.text) + "' has more than 3 indices");
    }
    if (part.empty()) {
      if (k == 1 && slash != std::string_view::npos) continue;  // v//vn
      fail(file, line, t.column, "'" + std::string(t.text) + "' is not a vertex reference");
    }
    int64_t index = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
    if (ec != std::errc() || end != part.data() + part.size() || index < INT32_MIN + 1 ||
        index > INT32_MAX) {
      fail(file, line, column, "'" + std::string(part) + "' is not a valid index");
    }
    const std::string_view name = kAttributeName[k];
    if (index == 0) {
      fail(file, line, column, std::string(name) + " index 0 is invalid (OBJ counts from 1)");
    }
    if (index < 0 && scan.count[k] + index < 0) {
      fail(file, line, column,
           std::string(name) + " index " + std::to_string(index) + " reaches before the first " +
               std::string(name) + " (" + std::to_string(scan.count[k]) + " defined above)");
    }
    if (index > scan.largest[k]) {
      scan.largest[k] = index;
      scan.largest_line[k] = line;
      scan.largest_column[k] = column;
    }
  }
}

/// Fails at line `line` (`s`) of `file`, an OBJ or MTL file (`format`), where it is UTF-16 (a
/// byte-order mark FF FE or FE FF opens line 1) or has a NUL byte. Text saved as "Unicode" is
/// UTF-16, where every other byte of ASCII is 0: no line read as a statement, and an OBJ file
/// was said to have no faces (a fresh user's trial), an MTL file's materials were never
/// declared.
void require_text_line(const std::string& file, size_t line, std::string_view s,
                       const char* format) {
  const auto rule = [&] { return std::string("; ") + format + " files must be ASCII or UTF-8"; };
  if (line == 1 && (s.starts_with("\xFF\xFE") || s.starts_with("\xFE\xFF"))) {
    fail(file, 1, 1,
         std::string("the file is UTF-16 (it starts with the byte-order mark ") +
             (s[0] == '\xFF' ? "FF FE" : "FE FF") + ")" + rule());
  }
  if (const size_t nul = s.find('\0'); nul != std::string_view::npos) {
    fail(file, line, nul + 1, "a NUL byte: the file is UTF-16 or not text" + rule());
  }
}

/// Checks one line of an OBJ file and records what it declares in `scan`.
void scan_obj_line(const std::string& file, size_t line, std::string_view s, ObjScan& scan) {
  // UTF-16 lines never pass scan_obj_line_fast, so the check costs the common lines nothing.
  require_text_line(file, line, s, "OBJ");
  Tokens tokens(s);
  const std::optional<Token> key = tokens.next();
  if (!key || key->text[0] == '#') return;
  const std::string_view k = key->text;
  if (k == "v" || k == "vn" || k == "vt") {
    const Attribute a = k == "v" ? kPosition : k == "vt" ? kTexcoord : kNormal;
    bool zero[3] = {true, true, true};
    int n = 0;
    while (const std::optional<Token> t = tokens.next()) {
      bool is_zero = false;
      if (!simple_decimal(t->text, is_zero)) is_zero = parse_number(file, line, *t) == 0.0f;
      if (n < 3) zero[n] = is_zero;
      ++n;
    }
    // v: x y z [w] or x y z r g b; vt: u [v [w]]; vn: x y z.
    const bool ok = a == kPosition   ? (n == 3 || n == 4 || n == 6)
                    : a == kTexcoord ? (n >= 1 && n <= 3)
                                     : n == 3;
    if (!ok) {
      fail(file, line, key->column,
           "'" + std::string(k) + "' has " + std::to_string(n) + " numbers, expected " +
               (a == kPosition   ? "3 (x y z), 4 or 6"
                : a == kTexcoord ? "1 to 3"
                                 : "3"));
    }
    if (a == kNormal && zero[0] && zero[1] && zero[2]) {
      if (scan.zero_normals++ == 0) scan.first_zero_normal_line = line;
    }
    if (a == kPosition && n == 6) {
      if (scan.coloured_vertices++ == 0) scan.first_coloured_line = line;
    }
    ++scan.count[a];
  } else if (k == "f") {
    int corners = 0;
    while (const std::optional<Token> t = tokens.next()) {
      scan_corner(file, line, *t, scan);
      ++corners;
    }
    if (corners < 3) {
      fail(file, line, key->column,
           "face has " + std::to_string(corners) + " vertices, fewer than 3");
    }
    if (corners > 255) {
      // tinyobjloader counts corners in an unsigned char.
      fail(file, line, key->column,
           "face has " + std::to_string(corners) + " vertices, more than 255");
    }
    if (corners > 3) scan.polygon_lines.push_back(line);
    ++scan.faces;
  } else if (k == "usemtl") {
    scan.usemtl.emplace_back(line, std::string(tokens.rest()));
  } else if (k == "mtllib") {
    while (const std::optional<Token> t = tokens.next()) {
      scan.mtllib_line.emplace(std::string(t->text), line);
    }
  } else if (k == "s") {
    // As LoadObj: "off" or a negative value is group 0, otherwise atoi's; no value, no change.
    const size_t start = key->column + 1;
    const std::string value(start < s.size() ? s.substr(start) : std::string_view());
    const size_t first = value.find_first_not_of(" \t");
    if (first != std::string::npos) {
      const int group = value.compare(first, 3, "off") == 0
                            ? 0
                            : int(std::strtol(value.c_str() + first, nullptr, 10));
      scan.smoothing.emplace_back(scan.faces, uint32_t(std::max(group, 0)));
    }
  } else if (k != "g" && k != "o") {
    scan.ignored.emplace(std::string(k), line);
  }
}

bool blank(char c) {
  return c == ' ' || c == '\t';
}

/// scan_obj_line for the lines that make up almost all of a large file, `v`, `vt` and `vn` of
/// plain decimals (as simple_decimal) and `f` of plain indices, in one pass over the characters
/// without tokens. Returns false, having changed nothing, for anything else, wrong lines
/// included: scan_obj_line then checks the line and names what is wrong. (The scan was a
/// quarter of the import's time before this path.)
bool scan_obj_line_fast(size_t line, std::string_view s, ObjScan& scan) {
  const char* p = s.data();
  const char* const end = p + s.size();
  while (p < end && blank(*p)) ++p;
  if (end - p < 2) return false;
  if (p[0] == 'v') {
    Attribute a = kPosition;
    if (blank(p[1])) {
      p += 1;
    } else if ((p[1] == 't' || p[1] == 'n') && end - p > 2 && blank(p[2])) {
      a = p[1] == 't' ? kTexcoord : kNormal;
      p += 2;
    } else {
      return false;
    }
    bool zero[3] = {true, true, true};
    int n = 0;
    for (;;) {
      while (p < end && blank(*p)) ++p;
      if (p == end) break;
      if (*p == '-' || *p == '+') ++p;
      bool is_zero = true;
      size_t integer = 0, digits = 0;
      for (; p < end && unsigned(*p - '0') < 10; ++p, ++integer) is_zero &= *p == '0';
      if (integer > 15) return false;
      digits = integer;
      if (p < end && *p == '.') {
        for (++p; p < end && unsigned(*p - '0') < 10; ++p, ++digits) is_zero &= *p == '0';
      }
      if (digits == 0 || (p < end && !blank(*p))) return false;
      if (n < 3) zero[n] = is_zero;
      ++n;
    }
    const bool ok = a == kPosition   ? (n == 3 || n == 4 || n == 6)
                    : a == kTexcoord ? (n >= 1 && n <= 3)
                                     : n == 3;
    if (!ok) return false;
    if (a == kNormal && zero[0] && zero[1] && zero[2]) {
      if (scan.zero_normals++ == 0) scan.first_zero_normal_line = line;
    }
    if (a == kPosition && n == 6) {
      if (scan.coloured_vertices++ == 0) scan.first_coloured_line = line;
    }
    ++scan.count[a];
    return true;
  }
  if (p[0] != 'f' || !blank(p[1])) return false;
  ++p;
  int64_t largest[3] = {scan.largest[0], scan.largest[1], scan.largest[2]};
  size_t largest_column[3] = {0, 0, 0};
  int corners = 0;
  for (;;) {
    while (p < end && blank(*p)) ++p;
    if (p == end) break;
    for (int k = 0; k < 3; ++k) {
      if (k == 1 && *p == '/') {  // v//vn
        ++p;
        k = 2;
      }
      const char* const start = p;
      const bool negative = p < end && *p == '-';
      if (negative) ++p;
      int64_t index = 0;
      int digits = 0;
      for (; p < end && unsigned(*p - '0') < 10 && digits <= 10; ++p, ++digits) {
        index = 10 * index + (*p - '0');
      }
      if (digits == 0 || digits > 10 || index > INT32_MAX || index == 0) return false;
      if (negative) {
        if (scan.count[k] - index < 0) return false;
      } else if (index > largest[k]) {
        largest[k] = index;
        largest_column[k] = size_t(start - s.data()) + 1;
      }
      if (p == end || blank(*p)) break;
      // A '/' needs an index after it, and there are at most three.
      if (*p != '/' || k == 2 || p + 1 == end || blank(p[1])) return false;
      ++p;
    }
    ++corners;
  }
  if (corners < 3 || corners > 255) return false;
  for (int k = 0; k < 3; ++k) {
    if (largest_column[k] != 0) {
      scan.largest[k] = largest[k];
      scan.largest_line[k] = line;
      scan.largest_column[k] = largest_column[k];
    }
  }
  if (corners > 3) scan.polygon_lines.push_back(line);
  ++scan.faces;
  return true;
}

/// The checks that need the whole file (indices against the final counts), and the scan's
/// warnings.
void finish_obj_scan(const std::string& file, const ObjScan& scan,
                     std::vector<std::string>& warnings) {
  for (int a = 0; a < 3; ++a) {
    if (scan.largest[a] > scan.count[a]) {
      const std::string name = kAttributeName[a];
      fail(file, scan.largest_line[a], scan.largest_column[a],
           name + " index " + std::to_string(scan.largest[a]) + " is out of range: the file has " +
               std::to_string(scan.count[a]) + " " +
               (scan.count[a] == 1 ? kAttributeName[a] : kAttributePlural[a]));
    }
  }
  if (scan.zero_normals > 0) {
    warnings.push_back(place(file, scan.first_zero_normal_line) + ": normal (0, 0, 0) has no " +
                       "direction (" + std::to_string(scan.zero_normals) +
                       " such in the file); corners using it get generated normals");
  }
  if (scan.coloured_vertices > 0) {
    warnings.push_back(place(file, scan.first_coloured_line) + ": vertex colours (" +
                       std::to_string(scan.coloured_vertices) +
                       " vertices with r g b) are ignored: Tessera's materials do not read them");
  }
  for (const auto& [keyword, line] : scan.ignored) {
    warnings.push_back(place(file, line) + ": '" + keyword +
                       "' statements are not supported and were ignored (" +
                       (keyword == "l" || keyword == "p" ? "Tessera draws only faces"
                                                         : "not a polygon statement") +
                       ")");
  }
}

// ---------------------------------------------------------------------------------------------
// MTL

struct MtlInfo {
  std::string file;                     // the library's path
  std::map<std::string, size_t> lines;  // keyword -> line of its last use ("newmtl" included)
};

/// Checks the numbers of an MTL file and records where each material's statements are.
void scan_mtl(const std::string& file, std::string_view text,
              std::map<std::string, MtlInfo>& materials) {
  static const char* const kNumeric[] = {"Ka", "Kd", "Ks", "Ke", "Ns",  "Ni",    "d",     "Tr",
                                         "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
  MtlInfo* current = nullptr;
  for_each_line(text, [&](size_t line, std::string_view s) {
    require_text_line(file, line, s, "MTL");
    Tokens tokens(s);
    const std::optional<Token> key = tokens.next();
    if (!key || key->text[0] == '#') return;
    const std::string keyword(key->text);
    if (keyword == "newmtl") {
      // As tinyobjloader names it: the rest of the line after "newmtl" and one separator.
      const size_t start = key->column - 1 + 7;
      current = &materials[start < s.size() ? std::string(s.substr(start)) : std::string()];
      current->file = file;
    }
    if (current) current->lines[keyword] = line;
    if (std::find(std::begin(kNumeric), std::end(kNumeric), keyword) == std::end(kNumeric)) {
      return;
    }
    int n = 0;
    float first = 0.0f;
    while (const std::optional<Token> t = tokens.next()) {
      const float x = parse_number(file, line, *t);
      if (n++ == 0) first = x;
      if (keyword == "Ke" && x < 0.0f) {
        fail(file, line, t->column, "emission 'Ke' must not be negative");
      }
    }
    if (n == 0) fail(file, line, key->column, "'" + keyword + "' has no value");
    if (keyword == "Ns" && first < 0.0f) {
      fail(file, line, key->column, "specular exponent 'Ns' must not be negative");
    }
  });
}

/// Reads the libraries named by `mtllib` for tinyobjloader, scanning each first. Errors and
/// warnings are kept and raised after tinyobjloader returns, not thrown through it.
class MtlReader : public tinyobj::MaterialReader {
 public:
  MtlReader(const std::string& obj_path, const std::string& base_dir, const ObjScan& scan,
            uint64_t max_bytes)
      : obj_path_(obj_path), base_dir_(base_dir), scan_(scan), max_bytes_(max_bytes) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* map, std::string* warn, std::string* err) override {
    material_map = map;
    std::string relative = name;
    std::replace(relative.begin(), relative.end(), '\\', '/');
    const std::string path = (fs::path(base_dir_) / fs::path(relative)).lexically_normal().string();
    const auto it = scan_.mtllib_line.find(name);
    const size_t line = it == scan_.mtllib_line.end() ? 0 : it->second;
    try {
      try {
        require_regular_file(path);  // a directory or a FIFO: an error, not "not found"
      } catch (const Error& e) {
        throw Error(place(obj_path_, line) + ": material library " + e.what());
      }
      const std::optional<std::string> text = read_limited(path, max_bytes_);
      if (!text) {
        warnings.push_back(place(obj_path_, line) + ": material library " + quoted(path) +
                           " not found; its materials are replaced by the default material");
        return false;
      }
      scan_mtl(path, *text, info);
      std::istringstream in(*text);
      const size_t first = materials->size();
      tinyobj::LoadMtl(map, materials, &in, warn, err);
      // tinyobjloader also keeps statements before any newmtl, as a material named "".
      for (size_t m = first; m < materials->size(); ++m) {
        info.try_emplace((*materials)[m].name, MtlInfo{path, {}});
      }
      return true;
    } catch (const Error& e) {
      if (!error) error = e.what();
      return false;
    }
  }

  std::map<std::string, MtlInfo> info;  // by material name
  // tinyobjloader's name -> material id, while it reads the OBJ file (after its first mtllib).
  const std::map<std::string, int>* material_map = nullptr;
  std::vector<std::string> warnings;
  std::optional<std::string> error;

 private:
  std::string obj_path_;
  std::string base_dir_;
  const ObjScan& scan_;
  uint64_t max_bytes_;
};

struct Importer {
  std::string path;
  ImportOptions options;
  ImportedModel model;
  std::map<std::string, uint32_t> texture_cache;            // key -> index into scene.textures
  std::map<std::pair<std::string, bool>, Texture> decoded;  // (file, srgb) -> decode_maps' image

  /// The file a map statement names, relative to its library.
  static std::string map_file(const MtlInfo& info, const std::string& name) {
    std::string relative = name;
    std::replace(relative.begin(), relative.end(), '\\', '/');
    return (fs::path(info.file).parent_path() / fs::path(relative)).lexically_normal().string();
  }

  /// Decodes the images of every map that the materials name, in parallel on every core, into
  /// `decoded`. Files that load_map would refuse (missing, too large) are left to it, so its
  /// warnings and errors stay where they were.
  void decode_maps(const std::vector<tinyobj::material_t>& materials,
                   const std::map<std::string, MtlInfo>& info) {
    std::vector<std::pair<std::string, bool>> wanted;
    for (const tinyobj::material_t& m : materials) {
      const auto library = info.find(m.name);
      if (library == info.end()) continue;
      const std::pair<const std::string*, bool> maps[] = {
          {&m.diffuse_texname, true},   {&m.emissive_texname, true}, {&m.roughness_texname, false},
          {&m.metallic_texname, false}, {&m.normal_texname, false},  {&m.bump_texname, false}};
      for (const auto& [name, srgb] : maps) {
        if (name->empty()) continue;
        const std::string file = map_file(library->second, *name);
        std::error_code ec;
        if (!fs::is_regular_file(file, ec) || fs::file_size(file, ec) > options.max_file_bytes) {
          continue;
        }
        int w = 0, h = 0, channels = 0;
        if (!stbi_info(file.c_str(), &w, &h, &channels) || uint32_t(w) > options.max_texture_side ||
            uint32_t(h) > options.max_texture_side) {
          continue;
        }
        wanted.emplace_back(file, srgb);
      }
    }
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    std::vector<std::optional<Texture>> images(wanted.size());
    parallel_for(wanted.size(), [&](size_t i) {
      try {
        images[i] = load_texture(wanted[i].first, wanted[i].second);
      } catch (const Error&) {
        // Left to load_map, which fails the same way naming the material.
      }
    });
    for (size_t i = 0; i < wanted.size(); ++i) {
      if (images[i]) decoded.emplace(wanted[i], std::move(*images[i]));
    }
  }

  void warn(const std::string& message) {
    if (options.strict) throw Error(message + " (a warning, an error in strict import)");
    model.warnings.push_back(message);
  }

  /// Where a material statement is, for messages.
  std::string where(const MtlInfo& info, const std::string& keyword,
                    const std::string& material) const {
    const auto it = info.lines.find(keyword);
    return place(info.file, it == info.lines.end() ? 0 : it->second) + " ('" + keyword +
           "' of material '" + material + "')";
  }

  /// The image a map statement names, or nullopt (with a warning) when the file is missing.
  std::optional<Texture> load_map(const MtlInfo& info, const std::string& keyword,
                                  const std::string& material, const std::string& name,
                                  const tinyobj::texture_option_t& option, bool srgb) {
    const std::string file = map_file(info, name);
    try {
      require_regular_file(file);  // a directory or a FIFO: an error, not "not found"
    } catch (const Error& e) {
      throw Error(where(info, keyword, material) + ": texture " + e.what());
    }
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
      warn(where(info, keyword, material) + ": texture " + quoted(file) +
           " not found; the material is drawn without it");
      return std::nullopt;
    }
    const uint64_t size = fs::file_size(file, ec);
    if (size > options.max_file_bytes) {
      throw Error(where(info, keyword, material) + ": texture " + quoted(file) + " is " +
                  std::to_string(size) + " bytes, over the limit of " +
                  std::to_string(options.max_file_bytes) + " (ImportOptions::max_file_bytes)");
    }
    // The header's size before anything is decoded (oversized_image), then whether stb_image
    // knows the format at all.
    try {
      const MappedFile bytes = tessera::map_file(file, options.max_file_bytes);
      if (const auto side =
              oversized_image({bytes.data(), bytes.size()}, options.max_texture_side)) {
        throw Error("texture " + quoted(file) + " is " + std::to_string(side->x) + "x" +
                    std::to_string(side->y) + ", over the largest side of " +
                    std::to_string(options.max_texture_side) +
                    " (ImportOptions::max_texture_side)");
      }
      int w = 0, h = 0, channels = 0;
      const int header = int(std::min<size_t>(bytes.size(), INT32_MAX));  // enough for a header
      if (!stbi_info_from_memory(bytes.data(), header, &w, &h, &channels)) {
        throw Error("cannot read texture " + quoted(file) + ": " + image_failure_reason());
      }
    } catch (const Error& e) {
      throw Error(where(info, keyword, material) + ": " + e.what());
    }
    // Names only the options the statement gives (a fresh user's trial: -clamp was named
    // where only -s and -o were given).
    std::string ignored;
    const auto ignore = [&](bool given, const char* name) {
      if (given) ignored += std::string(ignored.empty() ? "" : ", ") + name;
    };
    ignore(option.scale[0] != 1 || option.scale[1] != 1 || option.scale[2] != 1, "-s");
    ignore(option.origin_offset[0] != 0 || option.origin_offset[1] != 0 ||
               option.origin_offset[2] != 0,
           "-o");
    ignore(option.clamp, "-clamp");
    if (!ignored.empty()) {
      warn(where(info, keyword, material) + ": texture option" +
           (ignored.find(',') == std::string::npos ? " " : "s ") + ignored +
           (ignored.find(',') == std::string::npos ? " is" : " are") +
           " not supported and ignored");
    }
    try {
      // Taken, not copied: a second use of the file decodes it again.
      if (const auto it = decoded.find({file, srgb}); it != decoded.end()) {
        Texture t = std::move(it->second);
        decoded.erase(it);
        return t;
      }
      return load_texture(file, srgb);
    } catch (const Error& e) {
      throw Error(where(info, keyword, material) + ": " + e.what());
    }
  }

  uint32_t add_texture(const std::string& key, Texture texture) {
    const uint32_t index = uint32_t(model.scene.textures.size());
    model.scene.textures.push_back(std::move(texture));
    texture_cache.emplace(key, index);
    return index;
  }

  uint32_t cached(const std::string& key) const {
    const auto it = texture_cache.find(key);
    return it == texture_cache.end() ? kNoTexture : it->second;
  }

  /// One channel of a grayscale map: -imfchan r, g or b; otherwise red (gray images have
  /// R = G = B, and luminance would weight a coloured map arbitrarily).
  static int channel_of(const tinyobj::texture_option_t& option) {
    return option.imfchan == 'g' ? 1 : option.imfchan == 'b' ? 2 : 0;
  }

  /// map_Pr and map_Pm packed as glTF's metallic-roughness texture (G roughness, B metallic),
  /// at the larger of the two sizes (nearest texel of the smaller); a missing one reads 1.
  uint32_t metallic_roughness_map(const MtlInfo& info, const tinyobj::material_t& m) {
    const std::string key =
        "mr|" + info.file + "|" + m.roughness_texname + "|" + m.metallic_texname;
    if (const uint32_t index = cached(key); index != kNoTexture) return index;
    std::optional<Texture> rough, metal;
    if (!m.roughness_texname.empty()) {
      rough = load_map(info, "map_Pr", m.name, m.roughness_texname, m.roughness_texopt, false);
    }
    if (!m.metallic_texname.empty()) {
      metal = load_map(info, "map_Pm", m.name, m.metallic_texname, m.metallic_texopt, false);
    }
    if (!rough && !metal) return kNoTexture;
    Texture packed;
    packed.width = std::max(rough ? rough->width : 0u, metal ? metal->width : 0u);
    packed.height = std::max(rough ? rough->height : 0u, metal ? metal->height : 0u);
    packed.texels.assign(size_t(packed.width) * packed.height, glm::u8vec4(255));
    const auto copy = [&](const Texture& src, int from, int to) {
      for (uint32_t y = 0; y < packed.height; ++y) {
        for (uint32_t x = 0; x < packed.width; ++x) {
          const size_t sx = size_t(x) * src.width / packed.width;
          const size_t sy = size_t(y) * src.height / packed.height;
          packed.texels[size_t(y) * packed.width + x][to] = src.texels[sy * src.width + sx][from];
        }
      }
    };
    if (rough) copy(*rough, channel_of(m.roughness_texopt), 1);
    if (metal) copy(*metal, channel_of(m.metallic_texopt), 2);
    return add_texture(key, std::move(packed));
  }

  uint32_t plain_map(const MtlInfo& info, const std::string& keyword, const tinyobj::material_t& m,
                     const std::string& name, const tinyobj::texture_option_t& option, bool srgb) {
    const std::string key = (srgb ? "srgb|" : "linear|") + info.file + "|" + name;
    if (const uint32_t index = cached(key); index != kNoTexture) return index;
    std::optional<Texture> t = load_map(info, keyword, m.name, name, option, srgb);
    if (!t) return kNoTexture;
    if (keyword != "norm" && std::all_of(t->texels.begin(), t->texels.end(),
                                         [](glm::u8vec4 c) { return c.r == c.g && c.g == c.b; })) {
      warn(where(info, keyword, m.name) +
           ": the bump map is grayscale, so a height map, not a normal map; it was ignored");
      return kNoTexture;
    }
    return add_texture(key, std::move(*t));
  }

  float clamped(const MtlInfo& info, const std::string& keyword, const std::string& material,
                float value) {
    if (value >= 0.0f && value <= 1.0f) return value;
    warn(where(info, keyword, material) + ": " + std::to_string(value) +
         " is outside [0, 1] and was clamped");
    return std::clamp(value, 0.0f, 1.0f);
  }

  Material convert(const tinyobj::material_t& m, const MtlInfo& info) {
    const auto has = [&](const char* keyword) { return info.lines.count(keyword) > 0; };
    Material out;
    for (int c = 0; c < 3; ++c) out.base_color[c] = clamped(info, "Kd", m.name, m.diffuse[c]);
    if (has("Pr")) {
      out.roughness = clamped(info, "Pr", m.name, m.roughness);
    } else if (has("Ns")) {
      out.roughness = float(std::pow(2.0 / (double(m.shininess) + 2.0), 0.25));
    } else if (!m.roughness_texname.empty()) {
      out.roughness = 1.0f;  // the map alone defines it, as in glTF
    }
    if (has("Pm")) {
      out.metallic = clamped(info, "Pm", m.name, m.metallic);
    } else if (!m.metallic_texname.empty()) {
      out.metallic = 1.0f;
    }
    out.emissive = glm::vec3(m.emission[0], m.emission[1], m.emission[2]);
    if (!m.diffuse_texname.empty()) {
      out.base_color_map =
          plain_map(info, "map_Kd", m, m.diffuse_texname, m.diffuse_texopt, /*srgb=*/true);
    }
    if (!m.emissive_texname.empty()) {
      out.emissive_map =
          plain_map(info, "map_Ke", m, m.emissive_texname, m.emissive_texopt, /*srgb=*/true);
    }
    out.metallic_roughness_map = metallic_roughness_map(info, m);
    // `norm` is the PBR extension's normal map; `bump` is, strictly, a height map, but many
    // exporters write normal maps there (grayscale ones are refused in plain_map).
    const bool norm = !m.normal_texname.empty();
    const std::string& normal = norm ? m.normal_texname : m.bump_texname;
    const tinyobj::texture_option_t& normal_option = norm ? m.normal_texopt : m.bump_texopt;
    if (!normal.empty()) {
      const std::string keyword = norm ? "norm" : has("map_bump") ? "map_bump" : "bump";
      out.normal_map = plain_map(info, keyword, m, normal, normal_option, /*srgb=*/false);
      out.normal_scale = normal_option.bump_multiplier;
      if (!std::isfinite(out.normal_scale)) {
        throw Error(where(info, keyword, m.name) + ": -bm is not a finite number");
      }
    }
    if (m.dissolve < 1.0f) {
      warn(where(info, has("d") ? "d" : "Tr", m.name) +
           ": transparency is not supported; the material is rendered opaque");
    }
    const std::pair<const char*, const std::string*> ignored[] = {
        {"map_d", &m.alpha_texname},
        {"map_Ks", &m.specular_texname},
        {"map_Ns", &m.specular_highlight_texname},
        {"disp", &m.displacement_texname},
        {"map_Ka", &m.ambient_texname}};
    for (const auto& [keyword, name] : ignored) {
      if (!name->empty()) warn(where(info, keyword, m.name) + ": not supported, ignored");
    }
    return out;
  }
};

// ---------------------------------------------------------------------------------------------
// Polygons

/// Twice the signed area of (a, b, c) in the plane: > 0 when counter-clockwise.
double orient(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Splits a polygon (corners in order, counter-clockwise about `normal`) into n - 2 triangles
/// of corner numbers appended to `out`. Returns false if ear clipping found no ear somewhere
/// (a self-intersecting polygon), where it cut one anyway.
bool triangulate(const std::vector<glm::vec3>& corners, glm::vec3 normal,
                 std::vector<uint32_t>& out) {
  const size_t n = corners.size();
  if (n == 3) {
    out.insert(out.end(), {0u, 1u, 2u});
    return true;
  }
  // Project along the normal's largest axis, keeping the winding (right-handed pairs).
  const glm::vec3 a = glm::abs(normal);
  const int axis = a.x > a.y && a.x > a.z ? 0 : a.y > a.z ? 1 : 2;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const bool flip = normal[axis] < 0.0f;
  // On the stack for the usual few corners: an allocation per quad was a tenth of the import.
  glm::dvec2 few[16];
  std::vector<glm::dvec2> many(n > 16 ? n : 0);
  glm::dvec2* const p = n > 16 ? many.data() : few;
  for (size_t i = 0; i < n; ++i) {
    p[i] =
        flip ? glm::dvec2(corners[i][v], corners[i][u]) : glm::dvec2(corners[i][u], corners[i][v]);
  }
  // Wrapped by comparison, not %: two integer divisions per corner were most of a quad's time.
  const auto after = [n](size_t i) { return i + 1 == n ? 0 : i + 1; };
  bool convex = true;
  for (size_t i = 0; i < n && convex; ++i) {
    convex = orient(p[i], p[after(i)], p[after(after(i))]) >= 0.0;
  }
  if (convex) {
    for (uint32_t i = 1; i + 1 < n; ++i) out.insert(out.end(), {0u, i, i + 1});
    return true;
  }
  std::vector<uint32_t> left(n);
  for (uint32_t i = 0; i < n; ++i) left[i] = i;
  bool clean = true;
  while (left.size() > 3) {
    const size_t m = left.size();
    size_t ear = m;
    for (size_t i = 0; i < m && ear == m; ++i) {
      const uint32_t i0 = left[(i + m - 1) % m], i1 = left[i], i2 = left[(i + 1) % m];
      if (orient(p[i0], p[i1], p[i2]) <= 0.0) continue;  // reflex or flat: not an ear
      bool empty = true;
      for (size_t j = 0; j < m && empty; ++j) {
        const glm::dvec2 q = p[left[j]];
        if (q == p[i0] || q == p[i1] || q == p[i2]) continue;
        empty = !(orient(p[i0], p[i1], q) > 0.0 && orient(p[i1], p[i2], q) > 0.0 &&
                  orient(p[i2], p[i0], q) > 0.0);
      }
      if (empty) ear = i;
    }
    if (ear == m) {
      clean = false;
      ear = 1;
    }
    out.insert(out.end(), {left[(ear + m - 1) % m], left[ear], left[(ear + 1) % m]});
    left.erase(left.begin() + ptrdiff_t(ear));
  }
  out.insert(out.end(), {left[0], left[1], left[2]});
  return clean;
}

/// Newell's normal of a polygon: its direction is the polygon's facing, its length twice its
/// area, for any planar polygon (convex or not).
glm::vec3 newell_normal(const std::vector<glm::vec3>& corners) {
  glm::vec3 n(0.0f);
  for (size_t i = 0; i < corners.size(); ++i) {
    const glm::vec3& a = corners[i];
    const glm::vec3& b = corners[i + 1 == corners.size() ? 0 : i + 1];  // no division (as above)
    n += glm::vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  return n;
}

/// A unit normal for `n`, or +z for a zero one: a degenerate face covers no pixel, but the
/// scene needs unit normals everywhere.
glm::vec3 unit_or_z(glm::vec3 n) {
  const float length = glm::length(n);
  return length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
}

/// What makes two corners one vertex: the mesh being built, position, uv and normal source.
struct VertexKey {
  int32_t v, vt;
  int64_t normal;  // >= 0: a file normal; else -1 - smoothing group, or flat: kFlat - face
  uint32_t builder;
  bool operator==(const VertexKey&) const = default;
};
constexpr int64_t kFlat = INT64_MIN / 2;

struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    // splitmix64 finalizer over the packed fields
    uint64_t x = (uint64_t(uint32_t(k.v)) << 32 | uint32_t(k.vt)) ^
                 (uint64_t(k.normal) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(k.builder) << 17);
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return size_t(x ^ (x >> 31));
  }
};

// Corner key -> vertex index, open addressing with linear probing: one flat array, no node per
// vertex. Load factor at most 1/2. Values are stored plus one, 0 marking an empty slot.
class VertexTable {
 public:
  // The vertex of `key`, and whether it was just added with value `next`.
  std::pair<uint32_t, bool> emplace(const VertexKey& key, uint32_t next) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    size_t i = VertexKeyHash{}(key) & (slots_.size() - 1);
    for (;; i = (i + 1) & (slots_.size() - 1)) {
      Slot& s = slots_[i];
      if (s.value_plus_one == 0) {
        s = {key, next + 1};
        ++size_;
        return {next, true};
      }
      if (s.key == key) return {s.value_plus_one - 1, false};
    }
  }

 private:
  struct Slot {
    VertexKey key{};
    uint32_t value_plus_one = 0;
  };
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<size_t>(64, old.size() * 2), Slot{});
    size_ = 0;
    for (const Slot& s : old)
      if (s.value_plus_one != 0) emplace(s.key, s.value_plus_one - 1);
  }
  std::vector<Slot> slots_;
  size_t size_ = 0;
};

// Corner key -> vertex index for the meshes of one shape: a chain per position index of the
// vertices made from it. Faces refer to nearby positions, so the chains' heads are read almost
// in order, where a hash of the key missed the cache on nearly every corner (the conversion's
// largest cost at 10^7 triangles). A position with more than kLongChain vertices (the centre
// of a flat-shaded fan) moves to a hash table, so that no walk is long.
class VertexIndex {
 public:
  // The vertex of `key`, and whether it was just added with value `next`.
  std::pair<uint32_t, bool> emplace(const VertexKey& key, uint32_t next) {
    TESSERA_CHECK(size_t(key.v) < head_.size());  // cover()
    uint32_t& head = head_[size_t(key.v)];
    if (head == kCrowded) return crowded_.emplace(key, next);
    if (head == kNone) touched_.push_back(uint32_t(key.v));
    uint32_t length = 0;
    for (uint32_t n = head; n != kNone; n = nodes_[n].next, ++length) {
      const Node& node = nodes_[n];
      if (node.vt == key.vt && node.normal == key.normal && node.builder == key.builder) {
        return {node.vertex, false};
      }
    }
    if (length >= kLongChain) {
      for (uint32_t n = head; n != kNone; n = nodes_[n].next) {
        const Node& node = nodes_[n];
        crowded_.emplace({key.v, node.vt, node.normal, node.builder}, node.vertex);
      }
      head = kCrowded;
      return crowded_.emplace(key, next);
    }
    if (nodes_.size() >= kCrowded) throw Error("an OBJ shape has more than 2^32 - 2 vertices");
    nodes_.push_back({key.vt, key.builder, key.normal, next, head});
    head = uint32_t(nodes_.size() - 1);
    return {next, true};
  }

  // Room for position indices below `size`, growing by doubling up to `capacity`, the size
  // that ObjBuilder expects the positions to reach (positions arrive while faces are converted).
  // Not to `capacity` at once: the heads are written, and an estimate made while only `v` lines
  // had been read is several times the positions' count.
  void cover(size_t size, size_t capacity) {
    if (head_.size() < size) {
      head_.resize(std::min(std::max(2 * head_.size(), size), std::max(size, capacity)), kNone);
    }
  }

  // The nodes (one per vertex), for ObjBuilder::make_room's growth.
  size_t size() const { return nodes_.size(); }
  bool full() const { return nodes_.size() == nodes_.capacity(); }
  void reserve(size_t nodes) { nodes_.reserve(nodes); }

  // Forgets every vertex, before the next shape, and frees the memory that grows with them.
  void clear() {
    for (const uint32_t v : touched_) head_[v] = kNone;
    touched_ = {};
    nodes_ = {};
    crowded_ = {};
  }

 private:
  static constexpr uint32_t kNone = UINT32_MAX, kCrowded = UINT32_MAX - 1, kLongChain = 16;
  struct Node {
    int32_t vt;
    uint32_t builder;
    int64_t normal;
    uint32_t vertex, next;
  };
  std::vector<uint32_t> head_;     // per position index: its newest node, kNone or kCrowded
  std::vector<uint32_t> touched_;  // the position indices whose head is not kNone
  std::vector<Node> nodes_;
  VertexTable crowded_;
};

// The OBJ text as tinyobjloader reads it, scanned line by line (scan_obj_line) just before
// tinyobjloader gets each line: one pass over a file, read in chunks and never held whole, and
// the scan has seen a `mtllib` line when tinyobjloader asks for the library. The scan's first
// error ends the text (tinyobjloader sees the end of the file) and is kept in `error`, never
// thrown through tinyobjloader.
class ScanningBuffer : public std::streambuf {
 public:
  // Text held by the caller for the buffer's lifetime.
  ScanningBuffer(const std::string& path, std::string_view text, ObjScan& scan)
      : path_(path), scan_(scan), text_(text), size_(text.size()) {}
  // A file of `size` bytes read from its start (owned by the caller).
  ScanningBuffer(const std::string& path, FILE* file, uint64_t size, ObjScan& scan)
      : path_(path), scan_(scan), file_(file), chunk_(size_t(1) << 20), size_(size) {}

  std::optional<std::string> error;

  /// The text's size in bytes, and how much of it tinyobjloader has read.
  uint64_t size() const { return size_; }
  uint64_t position() const { return offset_ + uint64_t(gptr() - eback()); }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    if (error || done_) return traits_type::eof();
    try {
      if (!file_) {
        // All at once: the text is in memory already.
        const size_t used =
            split_lines(text_, /*last=*/true, line_, [&](size_t n, auto s) { scan_line(n, s); });
        char* begin = const_cast<char*>(text_.data());  // only read: a get area is non-const
        setg(begin, begin, begin + used);
        done_ = true;
      } else {
        // The part of the chunk after the last complete line moves to the front, and reading
        // continues until at least one line is complete (a line longer than the chunk grows it).
        size_t used = 0;
        while (used == 0 && !done_) {
          held_ -= scanned_;
          offset_ += scanned_;
          std::memmove(chunk_.data(), chunk_.data() + scanned_, held_);
          scanned_ = 0;
          if (held_ == chunk_.size()) chunk_.resize(2 * chunk_.size());
          held_ += std::fread(chunk_.data() + held_, 1, chunk_.size() - held_, file_);
          if (std::ferror(file_)) throw Error("cannot read " + quoted(path_));
          done_ = std::feof(file_) != 0;
          used = split_lines(std::string_view(chunk_.data(), held_), done_, line_,
                             [&](size_t n, auto s) { scan_line(n, s); });
        }
        scanned_ = used;
        setg(chunk_.data(), chunk_.data(), chunk_.data() + used);
      }
    } catch (const Error& e) {
      error = e.what();
      setg(nullptr, nullptr, nullptr);
      return traits_type::eof();
    }
    return gptr() < egptr() ? traits_type::to_int_type(*gptr()) : traits_type::eof();
  }

 private:
  void scan_line(size_t line, std::string_view s) {
    if (!scan_obj_line_fast(line, s, scan_)) scan_obj_line(path_, line, s, scan_);
  }

  const std::string& path_;
  ObjScan& scan_;
  std::string_view text_;
  FILE* file_ = nullptr;
  std::vector<char> chunk_;
  size_t held_ = 0;     // bytes of chunk_ read from the file
  size_t scanned_ = 0;  // of those, the complete lines handed to tinyobjloader
  size_t line_ = 0;     // lines scanned so far
  uint64_t size_ = 0;
  uint64_t offset_ = 0;  // of chunk_'s first byte in the file
  bool done_ = false;    // the whole text is scanned
};

struct MeshBuilder {
  int material = -1;
  Mesh mesh;
};

/// A face as tinyobjloader's index_cb reports it, with what the scan adds. Indices are 0-based
/// (-1: none), negative ones already resolved.
struct ObjFace {
  uint64_t shape = 0;  // `g` and `o` statements before it: faces of one shape share vertices
  int material = -1;   // tinyobjloader's material id, -1: none
  uint32_t group = 0;  // smoothing group, 0: flat
  uint32_t corners = 0;
  size_t line = 0;  // for a polygon (corners > 3)
};

// Turns the faces tinyobjloader's callbacks report into Tessera's meshes as they come: the
// attributes are kept once, as floats, and no face list exists beside the meshes. A face that
// refers to an attribute further down the file (OBJ readers accept that) waits, with every face
// after it, until the file is read.
class ObjBuilder {
 public:
  ObjBuilder(const std::string& path, ObjScan& scan, Scene& scene, const MtlReader& reader,
             const ScanningBuffer& text)
      : path_(path), scan_(scan), scene_(scene), reader_(reader), text_(text) {}

  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> texcoords;
  std::vector<tinyobj::material_t> materials;  // the libraries', in order
  std::vector<int> mesh_material;              // per mesh made: tinyobjloader's material id
  std::vector<std::string> polygon_warnings;   // self-intersecting polygons, in order
  std::optional<std::string> error;            // the first, kept (not thrown through tinyobj)

  static tinyobj::callback_t callbacks() {
    tinyobj::callback_t cb;
    cb.vertex_cb = [](void* self, float x, float y, float z, float) {
      ObjBuilder& b = *static_cast<ObjBuilder*>(self);
      b.make_room(b.positions, 0);
      b.positions.emplace_back(x, y, z);
    };
    cb.normal_cb = [](void* self, float x, float y, float z) {
      ObjBuilder& b = *static_cast<ObjBuilder*>(self);
      b.make_room(b.normals, 0);
      b.normals.emplace_back(x, y, z);
    };
    cb.texcoord_cb = [](void* self, float u, float v, float) {
      ObjBuilder& b = *static_cast<ObjBuilder*>(self);
      b.make_room(b.texcoords, 0);
      b.texcoords.emplace_back(u, v);
    };
    cb.index_cb = [](void* self, tinyobj::index_t* indices, int n) {
      static_cast<ObjBuilder*>(self)->add_face(indices, n);
    };
    cb.usemtl_cb = [](void* self, const char* name, int) {
      static_cast<ObjBuilder*>(self)->use_material(name);
    };
    cb.mtllib_cb = [](void* self, const tinyobj::material_t* m, int n) {
      static_cast<ObjBuilder*>(self)->materials.assign(m, m + n);
    };
    cb.group_cb = [](void* self, const char**, int) { ++static_cast<ObjBuilder*>(self)->shape_; };
    cb.object_cb = [](void* self, const char*) { ++static_cast<ObjBuilder*>(self)->shape_; };
    return cb;
  }

  /// Converts the faces that waited, after the file is read and its indices checked, and ends
  /// the last shape; then fills in the normals of smoothing groups, which need every face.
  void finish() {
    for (size_t f = 0, offset = 0; f < waiting_.size() && !error; ++f) {
      convert(waiting_[f], &waiting_indices_[offset]);
      offset += waiting_[f].corners;
    }
    waiting_ = {};
    waiting_indices_ = {};
    end_shape();
    vertices_ = {};
    if (smooth_.empty()) return;
    for (size_t m = first_mesh_; m < scene_.meshes.size(); ++m) {
      for (glm::vec3& n : scene_.meshes[m].normals) {
        if (!std::isnan(n.z)) continue;
        const uint64_t key =
            uint64_t(std::bit_cast<uint32_t>(n.y)) << 32 | std::bit_cast<uint32_t>(n.x);
        n = unit_or_z(smooth_.at(key));
      }
    }
  }

 private:
  /// Room for one more element at the end of `v`, which grows with the text from byte `since`
  /// on. Once that part is 1 MiB or more, a full `v` is given the capacity that the rest of the
  /// text would fill at the rate so far, plus 5 %, instead of twice its size: growing a large
  /// array copies it into fresh pages, and doubling does that about twice over its final size
  /// and holds both copies at its last step (at 10^7 triangles, on the loaded 2-core machine:
  /// 7.6 s of CPU time with doubling, 6.8 s with this, medians of 3 and 4 runs).
  /// Capacity beyond the size is never written, so an overestimate costs address space, not
  /// memory; it is bounded by two elements per byte left.
  template <typename T>
  void make_room(std::vector<T>& v, uint64_t since) {
    if (v.size() < v.capacity()) return;
    v.reserve(room_for(v.size(), since));
  }
  size_t room_for(size_t size, uint64_t since) const {
    const uint64_t at = text_.position(), total = text_.size();
    size_t want = std::max<size_t>(16, 2 * size);
    if (at >= since + (uint64_t(1) << 20) && total > at) {
      const double rate = double(size) / double(at - since);
      const size_t estimate =
          std::min(size_t(1.05 * rate * double(total - since)) + 16, size + 2 * size_t(total - at));
      want = std::max(estimate, size + size / 4 + 16);
    }
    return want;
  }

  // tinyobjloader names the material by the rest of the line; LoadObj (which import_obj used
  // before, and tests pin) by its first word, looked up when the line is read.
  void use_material(std::string_view rest) {
    const std::map<std::string, int>* map = reader_.material_map;
    const auto it =
        map ? map->find(material_name(rest, *map)) : std::map<std::string, int>::const_iterator();
    material_ = map && it != map->end() ? it->second : -1;
  }

  void add_face(const tinyobj::index_t* raw, int n) {
    ObjFace face{shape_, material_, group_, uint32_t(n), 0};
    while (!scan_.smoothing.empty() && scan_.smoothing.front().first <= faces_) {
      face.group = group_ = scan_.smoothing.front().second;
      scan_.smoothing.pop_front();
    }
    ++faces_;
    if (n > 3) {
      TESSERA_CHECK(!scan_.polygon_lines.empty());
      face.line = scan_.polygon_lines.front();
      scan_.polygon_lines.pop_front();
    }
    // 1-based, or negative: back from the last one read (the scan has checked both).
    const auto resolve = [](int index, size_t count) {
      return index > 0 ? index - 1 : index < 0 ? int(count) + index : -1;
    };
    corners_.resize(size_t(n));
    bool ready = waiting_.empty();
    for (int c = 0; c < n; ++c) {
      tinyobj::index_t& i = corners_[size_t(c)];
      i.vertex_index = resolve(raw[c].vertex_index, positions.size());
      i.texcoord_index = resolve(raw[c].texcoord_index, texcoords.size());
      i.normal_index = resolve(raw[c].normal_index, normals.size());
      ready &= size_t(i.vertex_index) < positions.size() &&
               i.texcoord_index < int64_t(texcoords.size()) &&
               i.normal_index < int64_t(normals.size());
    }
    if (ready) {
      convert(face, corners_.data());
    } else {
      waiting_.push_back(face);
      waiting_indices_.insert(waiting_indices_.end(), corners_.begin(), corners_.end());
    }
  }

  // A corner's file normal, unless it has none or a zero one (see scan_obj).
  std::optional<glm::vec3> file_normal(const tinyobj::index_t& index) const {
    if (index.normal_index < 0) return std::nullopt;
    const glm::vec3 n = normals[size_t(index.normal_index)];
    if (n == glm::vec3(0.0f)) return std::nullopt;
    return n;
  }

  void convert(const ObjFace& face, const tinyobj::index_t* indices) {
    if (error) return;
    try {
      convert_face(face, indices);
    } catch (const Error& e) {
      error = e.what();
    }
  }

  void convert_face(const ObjFace& face, const tinyobj::index_t* indices) {
    if (face.shape != current_shape_) {
      end_shape();
      current_shape_ = face.shape;
    }
    if (builders_.empty()) shape_start_ = text_.position();
    // One mesh per material, in order of first use in the shape.
    auto b = std::find_if(builders_.begin(), builders_.end(),
                          [&](const MeshBuilder& x) { return x.material == face.material; });
    if (b == builders_.end()) {
      builders_.emplace_back().material = face.material;
      b = builders_.end() - 1;
    }
    const uint32_t builder = uint32_t(b - builders_.begin());
    Mesh& mesh = b->mesh;
    const size_t n = face.corners;
    corners_xyz_.resize(n);
    for (size_t c = 0; c < n; ++c) corners_xyz_[c] = positions[size_t(indices[c].vertex_index)];
    const glm::vec3 face_normal = newell_normal(corners_xyz_);
    vertices_.cover(positions.size(), positions.capacity());
    // Smoothing groups: area-weighted normal sums per (group, position), over every shape, in
    // file order; the vertices get them in finish().
    const auto smooth_key = [&](const tinyobj::index_t& index) {
      return uint64_t(face.group) << 32 | uint32_t(index.vertex_index);
    };
    if (face.group > 0) {
      for (size_t c = 0; c < n; ++c) {
        if (!file_normal(indices[c])) smooth_[smooth_key(indices[c])] += face_normal;
      }
    }
    corner_vertex_.resize(n);
    for (size_t c = 0; c < n; ++c) {
      const tinyobj::index_t& index = indices[c];
      const std::optional<glm::vec3> given = file_normal(index);
      VertexKey key{index.vertex_index, index.texcoord_index, index.normal_index, builder};
      if (!given) key.normal = face.group > 0 ? -1 - int64_t(face.group) : kFlat - face_serial_;
      if (vertices_.full()) vertices_.reserve(room_for(vertices_.size(), shape_start_));
      const auto [vertex, inserted] = vertices_.emplace(key, uint32_t(mesh.positions.size()));
      if (inserted) {
        make_room(mesh.positions, shape_start_);
        make_room(mesh.normals, shape_start_);
        make_room(mesh.uvs, shape_start_);
        if (mesh.positions.size() == UINT32_MAX) {
          throw Error(quoted(path_) + ": a mesh has more than 2^32 - 1 vertices");
        }
        mesh.positions.push_back(corners_xyz_[c]);
        if (given) {
          mesh.normals.push_back(unit_or_z(*given));
        } else if (face.group > 0) {
          // Filled in by finish(): the key in x and y, and z NaN, which no normal read or made
          // here is (the scan refuses numbers that are not finite).
          mesh.normals.emplace_back(std::bit_cast<float>(uint32_t(smooth_key(index))),
                                    std::bit_cast<float>(face.group),
                                    std::numeric_limits<float>::quiet_NaN());
        } else {
          mesh.normals.push_back(unit_or_z(face_normal));
        }
        glm::vec2 uv(0.0f);
        if (index.texcoord_index >= 0) {
          const glm::vec2 vt = texcoords[size_t(index.texcoord_index)];
          uv = glm::vec2(vt.x, 1.0f - vt.y);
        }
        mesh.uvs.push_back(uv);
      }
      corner_vertex_[c] = vertex;
    }
    triangles_.clear();
    if (!triangulate(corners_xyz_, face_normal, triangles_)) {
      polygon_warnings.push_back(place(path_, face.line) +
                                 ": the polygon intersects itself; its triangulation is arbitrary");
    }
    for (uint32_t t : triangles_) {
      make_room(mesh.indices, shape_start_);
      mesh.indices.push_back(corner_vertex_[t]);
    }
    ++face_serial_;
  }

  void end_shape() {
    vertices_.clear();
    for (MeshBuilder& b : builders_) {
      // Not trimmed to size: capacity beyond the size (make_room's estimate, or doubling) was
      // never written, so it is address space, not memory, and a trim would copy each array
      // into fresh pages (at 10^6 triangles, a sixth more peak memory).
      Mesh& m = b.mesh;
      scene_.meshes.push_back(std::move(m));
      mesh_material.push_back(b.material);
    }
    builders_.clear();
  }

  const std::string& path_;
  ObjScan& scan_;
  Scene& scene_;
  const MtlReader& reader_;
  const ScanningBuffer& text_;
  const size_t first_mesh_ = scene_.meshes.size();
  uint64_t shape_ = 0, current_shape_ = 0;
  uint64_t shape_start_ = 0;  // where tinyobjloader was in the text at the shape's first face
  int material_ = -1;
  uint32_t group_ = 0;
  uint64_t faces_ = 0;                 // faces reported so far
  int64_t face_serial_ = 0;            // faces converted so far
  std::vector<MeshBuilder> builders_;  // the current shape's
  VertexIndex vertices_;
  std::unordered_map<uint64_t, glm::vec3> smooth_;
  std::vector<ObjFace> waiting_;
  std::vector<tinyobj::index_t> waiting_indices_;
  // Per face, kept to reuse their memory.
  std::vector<tinyobj::index_t> corners_;
  std::vector<glm::vec3> corners_xyz_;
  std::vector<uint32_t> corner_vertex_, triangles_;
};

ImportedModel import_obj_scanned(ScanningBuffer& buffer, ObjScan& scan, const std::string& path,
                                 const std::string& base_dir, const ImportOptions& options);

}  // namespace

ImportedModel import_obj(const std::string& path, const ImportOptions& options) {
  require_regular_file(path);  // a directory or a FIFO is said to be one, not "not found"
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error("OBJ file " + quoted(path) + " not found");
  const uint64_t size = fs::file_size(path, ec);
  if (ec) throw Error("cannot read " + quoted(path) + ": " + ec.message());
  check_size(path, size, options.max_file_bytes);
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) throw Error("cannot read " + quoted(path));
  ObjScan scan;
  ScanningBuffer buffer(path, file.get(), size, scan);
  return import_obj_scanned(buffer, scan, path, fs::path(path).parent_path().string(), options);
}

ImportedModel import_obj_text(const std::string& text, const std::string& path,
                              const std::string& base_dir, const ImportOptions& options) {
  check_size(path, text.size(), options.max_file_bytes);
  ObjScan scan;
  ScanningBuffer buffer(path, text, scan);
  return import_obj_scanned(buffer, scan, path, base_dir, options);
}

namespace {

ImportedModel import_obj_scanned(ScanningBuffer& buffer, ObjScan& scan, const std::string& path,
                                 const std::string& base_dir, const ImportOptions& options) {
  Importer im{path, options, {}, {}};
  Scene& scene = im.model.scene;
  std::string tiny_warn, tiny_err;
  MtlReader reader(path, base_dir, scan, options.max_file_bytes);
  ObjBuilder builder(path, scan, scene, reader, buffer);
  std::istream in(&buffer);
  const bool ok = tinyobj::LoadObjWithCallback(in, ObjBuilder::callbacks(), &builder, &reader,
                                               &tiny_warn, &tiny_err);
  // The scan's errors come first, as if it had read the whole file before tinyobjloader.
  if (buffer.error) throw Error(*buffer.error);
  std::vector<std::string> scan_warnings;
  finish_obj_scan(path, scan, scan_warnings);
  for (const std::string& w : scan_warnings) im.warn(w);
  if (scan.faces == 0) {
    throw Error(quoted(path) + " has no faces ('f' statements); Tessera draws only faces");
  }
  if (reader.error) throw Error(*reader.error);
  if (!ok || !tiny_err.empty()) throw Error(quoted(path) + ": tinyobjloader: " + tiny_err);
  for (const std::string& w : reader.warnings) im.warn(w);
  // tinyobjloader's own warnings repeat what the scans report with a line, or what is handled
  // below (material names); the others are passed on.
  {
    std::istringstream lines(tiny_warn);
    std::string line;
    const char* const known[] = {"material [", "Failed to load material", "Empty group name"};
    while (std::getline(lines, line)) {
      if (line.empty() || line == ".") continue;
      const bool repeat = std::any_of(std::begin(known), std::end(known),
                                      [&](const char* k) { return line.rfind(k, 0) == 0; });
      if (!repeat) im.warn(quoted(path) + ": tinyobjloader: " + line);
    }
  }
  TESSERA_CHECK(builder.positions.size() == size_t(scan.count[kPosition]));
  TESSERA_CHECK(builder.normals.size() == size_t(scan.count[kNormal]));
  TESSERA_CHECK(builder.texcoords.size() == size_t(scan.count[kTexcoord]));
  builder.finish();
  if (builder.error) throw Error(*builder.error);

  // Materials, in the libraries' order; one default material for faces without one.
  const std::vector<tinyobj::material_t>& materials = builder.materials;
  im.decode_maps(materials, reader.info);
  for (const tinyobj::material_t& m : materials) {
    const auto it = reader.info.find(m.name);
    TESSERA_CHECK(it != reader.info.end());
    scene.materials.push_back(im.convert(m, it->second));
  }
  std::set<std::string> names, warned;
  for (const tinyobj::material_t& m : materials) names.insert(m.name);
  for (const auto& [line, rest] : scan.usemtl) {
    // Once per name, at its first use: a file without its library names each material often.
    if (!names.count(material_name(rest, names)) && warned.insert(rest).second) {
      im.warn(place(path, line) + ": material '" + rest +
              "' is not defined in any material library; the default material is used");
    }
  }
  uint32_t default_material = kNoTexture;
  const auto material_index = [&](int id) {
    if (id >= 0 && size_t(id) < materials.size()) return uint32_t(id);
    if (default_material == kNoTexture) {
      default_material = uint32_t(scene.materials.size());
      scene.materials.push_back(Material{});
    }
    return default_material;
  };
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    Object object;
    object.mesh = uint32_t(m);
    object.material = material_index(builder.mesh_material[m]);
    scene.objects.push_back(object);
  }
  for (const std::string& w : builder.polygon_warnings) im.warn(w);
  return std::move(im.model);
}

}  // namespace

size_t obj_vertex_line(const std::string& path, const std::function<bool(glm::vec3)>& pick) {
  std::optional<std::string> text;
  try {
    text = read_limited(path, UINT64_MAX);
  } catch (const Error&) {
  }
  if (!text) return 0;
  size_t found = 0;
  for_each_line(*text, [&](size_t line, std::string_view s) {
    if (found) return;
    Tokens tokens(s);
    const std::optional<Token> key = tokens.next();
    if (!key || key->text != "v") return;
    glm::vec3 p(0.0f);
    for (int k = 0; k < 3; ++k) {
      const std::optional<Token> t = tokens.next();
      if (!t) return;
      std::string_view n = t->text;
      if (!n.empty() && n[0] == '+') n.remove_prefix(1);
      double value = 0.0;
      std::from_chars(n.data(), n.data() + n.size(), value);
      p[k] = float(value);
    }
    if (pick(p)) found = line;
  });
  return found;
}

}  // namespace tessera
