#include "host/cli_values.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/check.h"
#include "core/closest_name.h"
#include "core/file_extension.h"
#include "core/image.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {
namespace {

std::string in_quotes(const std::string& text) {
  return "'" + text + "'";
}

// ", got 'text'", saying so where `text` is another option: the parser takes the word after an
// option as its value, so an option given without one reads the next option as it.
std::string got(const std::string& text) {
  const bool option = text.size() > 2 && text.compare(0, 2, "--") == 0;
  return ", got " + in_quotes(text) + (option ? " (an option: is this one's value missing?)" : "");
}

// Empty if `text` is a whole number in [min, max], else what is wrong with it.
std::string whole_number_error(const std::string& text, uint64_t min, uint64_t max) {
  uint64_t value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < min || value > max) {
    return "expects a whole number from " + std::to_string(min) + " to " + std::to_string(max) +
           got(text);
  }
  return "";
}

}  // namespace

std::string list_of_choices(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return out;
}

CLI::Validator whole_number(uint64_t min, uint64_t max) {
  return CLI::Validator(
      [min, max](std::string& text) { return whole_number_error(text, min, max); }, "");
}

CLI::Validator finite_number(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        double value = 0;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
            value < min || value > max) {
          char range[64];
          std::snprintf(range, sizeof(range), "%g to %g", min, max);
          return std::string("expects a number from ") + range + got(text);
        }
        return "";
      },
      "");
}

CLI::Validator one_of(const std::vector<std::string>& names) {
  return CLI::Validator(
      [names](std::string& text) -> std::string {
        // Names are spelt with '-' here and with '_' in scene files (--brdf blinn-phong,
        // "brdf": "blinn_phong"); either is taken in both places (add_choice's setter too).
        std::string spelled = text;
        std::replace(spelled.begin(), spelled.end(), '_', '-');
        for (const std::string& name : names) {
          if (name == spelled) return "";
        }
        // A slip of case or of a letter or two ("Analytic", "filamint") names what was meant.
        const std::string near = closest_name(spelled, names);
        return "expects " + list_of_choices(names) + got(text) +
               (near.empty() ? "" : ", did you mean " + in_quotes(near) + "?");
      },
      "");
}

CLI::Validator image_size() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const size_t x = text.find('x');
        if (x == std::string::npos) return "expects WxH (e.g. 512x512)" + got(text);
        for (const auto& [side, digits] :
             {std::pair{"width", text.substr(0, x)}, std::pair{"height", text.substr(x + 1)}}) {
          const std::string error = whole_number_error(digits, 1, TS_MAX_IMAGE_SIDE);
          if (!error.empty()) return std::string(side) + " " + error + " in " + in_quotes(text);
        }
        return "";
      },
      "");
}

std::pair<uint32_t, uint32_t> read_size(const std::string& text) {
  const size_t x = text.find('x');
  TESSERA_CHECK(x != std::string::npos);  // image_size() accepted it
  return {uint32_t(std::stoul(text.substr(0, x))), uint32_t(std::stoul(text.substr(x + 1)))};
}

CLI::Validator file_with_suffix(const std::vector<std::string>& suffixes,
                                const std::vector<std::string>& also) {
  return CLI::Validator(
      [suffixes, also](std::string& text) -> std::string {
        for (const std::string& word : also) {
          if (text == word) return "";
        }
        for (const std::string& suffix : suffixes) {
          if (has_extension(text, suffix)) return "";
        }
        std::vector<std::string> choices;
        for (const std::string& suffix : suffixes) choices.push_back("a " + suffix + " file");
        choices.insert(choices.end(), also.begin(), also.end());
        return "expects " + list_of_choices(choices) + got(text);
      },
      "");
}

CLI::Validator writable_output() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::string why = unwritable_reason(text);
        return why.empty() ? "" : "cannot write " + in_quotes(text) + ": " + why;
      },
      "");
}

CLI::Validator checked_by(std::function<void(const std::string&)> check) {
  return CLI::Validator(
      [check](std::string& text) -> std::string {
        try {
          check(text);
        } catch (const Error& e) {
          return e.what();
        }
        return "";
      },
      "");
}

}  // namespace tessera
