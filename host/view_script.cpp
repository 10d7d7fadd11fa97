#include "host/view_script.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/check.h"
#include "core/file_extension.h"
#include "core/mapped_file.h"
#include "core/materials.h"
#include "core/scene.h"
#include "shaders/shared/constants.h"

namespace tessera {
namespace {

// Each event's form, for messages about a line that lacks a value.
const std::pair<const char*, const char*> kUsages[] = {
    {"key", "key NAME [ctrl] [shift]"},
    {"drag", "drag left|middle X0 Y0 X1 Y1 [shift]"},
    {"click", "click X Y"},
    {"wheel", "wheel NOTCHES"},
    {"resize", "resize W H"},
    {"screenshot", "screenshot PATH.png"},
    {"material", "material preset NAME | base_color|emissive R G B | metallic|roughness X"},
    {"light", "light add | light N delete|position X Y Z|color R G B|intensity X"},
    {"brdf", "brdf classic|filament|blinn-phong"},
    {"tonemap", "tonemap aces|reinhard|clamp"},
    {"exposure", "exposure EV"},
    {"energy_compensation", "energy_compensation on|off"},
    {"view", "view shaded|normal|uv|triangle|object"},
};

struct Line {
  const std::string& file;
  size_t number;
  std::vector<std::string> words;
  size_t next = 1;  // words[0] is the frame

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(file + ":" + std::to_string(number) + ": " + what);
  }
  bool more() const { return next < words.size(); }
  const std::string& word(const char* what) {
    if (!more()) {
      if (next == 1) fail(std::string("missing ") + what);
      // Which argument of which event, and the event's whole form.
      std::string usage;
      for (const auto& [kind, form] : kUsages)
        if (words[1] == kind) usage = std::string(" (") + form + ")";
      fail(words[1] + ": missing " + what + usage);
    }
    return words[next++];
  }
  // One of `choices` (its index), or a failure listing them.
  uint32_t choice(const char* what, const std::vector<std::string>& choices) {
    const std::string& w = word(what);
    // As on the command line: blinn_phong, the scene files' spelling, is blinn-phong.
    std::string spelled = w;
    std::replace(spelled.begin(), spelled.end(), '_', '-');
    for (size_t i = 0; i < choices.size(); ++i)
      if (spelled == choices[i]) return uint32_t(i);
    std::string list;
    for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
    fail("unknown " + std::string(what) + " '" + w + "' (" + list + ")");
  }
  // A range's end as written: whole numbers in full, the scene's limits (1e+26) as %g.
  static std::string bound(double v) {
    if (v == std::floor(v) && std::abs(v) < 1e9) return std::to_string(int64_t(v));
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
  }
  double number_of(const char* what, double min, double max) {
    const std::string& w = word(what);
    double value = 0.0;
    auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
    // Compared as the floats the events hold: 1e15 is kMaxSceneCoordinate once rounded.
    const bool within = float(value) >= float(min) && float(value) <= float(max);
    if (ec != std::errc() || end != w.data() + w.size() || !within) {
      fail(std::string(what) + " expects a number from " + bound(min) + " to " + bound(max) +
           ", got '" + w + "'");
    }
    return value;
  }
  uint32_t side(const char* what) {
    const double v = number_of(what, 1, TS_MAX_IMAGE_SIDE);
    if (v != double(uint32_t(v))) fail(std::string(what) + " expects a whole number");
    return uint32_t(v);
  }
  // A point in window pixels, its coordinates named as the event's form names them (X0 Y0 ...).
  glm::vec2 position(const char* x_name, const char* y_name) {
    const float x = float(number_of(x_name, 0, 65535));
    return {x, float(number_of(y_name, 0, 65535))};
  }
  void modifiers(InputEvent& e, bool allow_ctrl) {
    while (more()) {
      const std::string& w = words[next++];
      if (w == "shift") {
        e.shift = true;
      } else if (w == "ctrl" && allow_ctrl) {
        e.ctrl = true;
      } else {
        fail("unexpected '" + w + "'" +
             (allow_ctrl ? " (modifiers are ctrl and shift)" : " (the modifier is shift)"));
      }
    }
  }
  void end() const {
    if (more()) fail("unexpected '" + words[next] + "'");
  }
};

int key_code(const std::string& name) {
  if (name.size() == 1 &&
      ((name[0] >= 'A' && name[0] <= 'Z') || (name[0] >= '0' && name[0] <= '9')))
    return name[0];  // GLFW numbers letter and digit keys by their ASCII capitals
  if (name.size() >= 2 && name[0] == 'F') {
    int n = 0;
    auto [end, ec] = std::from_chars(name.data() + 1, name.data() + name.size(), n);
    if (ec == std::errc() && end == name.data() + name.size() && n >= 1 && n <= 12)
      return GLFW_KEY_F1 + n - 1;
  }
  const std::pair<const char*, int> named[] = {
      {"Delete", GLFW_KEY_DELETE}, {"Escape", GLFW_KEY_ESCAPE}, {"Space", GLFW_KEY_SPACE},
      {"Left", GLFW_KEY_LEFT},     {"Right", GLFW_KEY_RIGHT},   {"Up", GLFW_KEY_UP},
      {"Down", GLFW_KEY_DOWN},     {"Home", GLFW_KEY_HOME}};
  for (const auto& [n, code] : named) {
    if (name == n) return code;
  }
  return -1;
}

InputEvent parse_event(Line& line) {
  InputEvent e;
  const std::string& kind = line.word("event");
  if (kind == "key") {
    e.kind = EventKind::key;
    const std::string& name = line.word("key name");
    e.key = key_code(name);
    if (e.key < 0) {
      line.fail("unknown key '" + name +
                "' (A..Z, 0..9, F1..F12, Delete, Escape, Space, Left, Right, Up, Down, Home; "
                "modifiers follow the key: `key Z ctrl`)");
    }
    line.modifiers(e, true);
  } else if (kind == "drag") {
    e.kind = EventKind::drag;
    const std::string& button = line.word("button");
    if (button == "left") {
      e.button = MouseButton::left;
    } else if (button == "middle") {
      e.button = MouseButton::middle;
    } else {
      // A right drag does nothing in the window, so a script line with one is a mistake.
      line.fail("unknown button '" + button + "' (left orbits, middle pans)");
    }
    e.from = line.position("X0", "Y0");
    e.to = line.position("X1", "Y1");
    line.modifiers(e, false);
  } else if (kind == "click") {
    e.kind = EventKind::click;
    e.from = line.position("X", "Y");
    line.end();
  } else if (kind == "wheel") {
    e.kind = EventKind::wheel;
    e.wheel = float(line.number_of("notches", -1000, 1000));
    line.end();
  } else if (kind == "resize") {
    e.kind = EventKind::resize;
    e.width = line.side("width");
    e.height = line.side("height");
    line.end();
  } else if (kind == "minimise" || kind == "minimize") {
    e.kind = EventKind::minimise;
    line.end();
  } else if (kind == "restore") {
    e.kind = EventKind::restore;
    line.end();
  } else if (kind == "screenshot") {
    e.kind = EventKind::screenshot;
    e.path = line.word("PNG path");
    if (!has_extension(e.path, ".png"))
      line.fail("screenshot expects a .png path, got '" + e.path + "'");
    line.end();
  } else if (kind == "save") {
    e.kind = EventKind::save;
    if (line.more()) e.path = line.word("path");
    line.end();
  } else if (kind == "exit") {
    e.kind = EventKind::exit;
    line.end();
  } else if (kind == "material") {
    e.kind = EventKind::material;
    e.field = line.word("material field");
    if (e.field == "preset") {
      e.path = line.word("preset name");
      if (!find_metal_preset(e.path)) line.fail("unknown metal preset '" + e.path + "'");
    } else if (e.field == "base_color" || e.field == "emissive") {
      const float limit = e.field == "emissive" ? 1e6f : 1.0f;
      for (int c = 0; c < 3; ++c) e.value[c] = float(line.number_of("colour component", 0, limit));
    } else if (e.field == "metallic" || e.field == "roughness") {
      e.value.x = float(line.number_of(e.field.c_str(), 0, 1));
    } else {
      line.fail("unknown material field '" + e.field +
                "' (preset, base_color, metallic, roughness or emissive)");
    }
    line.end();
  } else if (kind == "light") {
    e.kind = EventKind::light;
    if (line.more() && line.words[line.next] == "add") {
      e.field = line.word("light action");
      line.end();
      return e;
    }
    const double index = line.number_of("light index", 0, 65535);
    if (index != double(uint32_t(index))) line.fail("light index expects a whole number");
    e.index = uint32_t(index);
    e.field = line.word("light action");
    if (e.field == "position") {
      // The scene's own limits (validate_scene), so that a script can set what a scene file can.
      for (int c = 0; c < 3; ++c) {
        e.value[c] = float(line.number_of("coordinate", -kMaxSceneCoordinate, kMaxSceneCoordinate));
      }
    } else if (e.field == "color") {
      for (int c = 0; c < 3; ++c) e.value[c] = float(line.number_of("colour component", 0, 1e6));
    } else if (e.field == "intensity") {
      e.value.x = float(line.number_of("intensity", 0, kMaxLightIntensity));
    } else if (e.field != "delete") {
      line.fail("unknown light action '" + e.field +
                "' (add, or after the light's index: delete, position, color, intensity)");
    }
    line.end();
  } else if (kind == "memory") {
    e.kind = EventKind::memory;
    line.end();
  } else if (kind == "brdf" || kind == "tonemap" || kind == "view" ||
             kind == "energy_compensation") {
    // The choices in the order of their enums (core/scene.h), as the command line spells them.
    e.kind = EventKind::option;
    e.field = kind;
    e.index = kind == "brdf"      ? line.choice("BRDF", {"classic", "filament", "blinn-phong"})
              : kind == "tonemap" ? line.choice("tone map", {"aces", "reinhard", "clamp"})
              : kind == "view"
                  ? line.choice("view", {"shaded", "normal", "uv", "triangle", "object"})
                  : line.choice("setting", {"off", "on"});
    line.end();
  } else if (kind == "exposure") {
    e.kind = EventKind::option;
    e.field = kind;
    e.value.x = float(line.number_of("exposure", -64, 64));
    line.end();
  } else {
    line.fail("unknown event '" + kind +
              "' (key, drag, click, wheel, resize, minimise, restore, screenshot, save, exit, "
              "memory, material, light, brdf, tonemap, exposure, energy_compensation, view)");
  }
  return e;
}

}  // namespace

std::vector<ScriptEvent> parse_view_script(const std::string& text, const std::string& file) {
  std::vector<ScriptEvent> events;
  std::istringstream in(text);
  std::string raw;
  for (size_t number = 1; std::getline(in, raw); ++number) {
    raw = raw.substr(0, raw.find('#'));
    Line line{file, number, {}};
    std::istringstream words(raw);
    for (std::string w; words >> w;) line.words.push_back(w);
    if (line.words.empty()) continue;
    const std::string& frame = line.words[0];
    ScriptEvent event;
    auto [end, ec] = std::from_chars(frame.data(), frame.data() + frame.size(), event.frame);
    if (ec != std::errc() || end != frame.data() + frame.size()) {
      line.fail("expects a frame number first, got '" + frame + "'");
    }
    if (!events.empty() && event.frame < events.back().frame) {
      line.fail("frame " + frame + " comes before the previous line's frame " +
                std::to_string(events.back().frame));
    }
    event.event = parse_event(line);
    event.event.scripted = true;
    events.push_back(std::move(event));
  }
  return events;
}

std::vector<ScriptEvent> load_view_script(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("script file '" + path + "' not found");
  require_regular_file(path);  // before it is opened: a FIFO would block the open
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error("cannot read script file '" + path + "': " + std::strerror(errno));
  std::stringstream text;
  text << file.rdbuf();
  return parse_view_script(text.str(), path);
}

}  // namespace tessera
