#pragma once
// Validators of option values for the `tessera` command line (CLI11). Each checks the text of
// one value before CLI11 converts it, and names what was expected and what was given; CLI11
// prefixes the option's name ("--size: ..."). Parsing and error reporting are in host/cli.cpp.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace tessera {

/// A whole number in [min, max] (decimal digits only: no sign, no spaces).
CLI::Validator whole_number(uint64_t min, uint64_t max);

/// A finite number (as std::from_chars reads it) in [min, max].
CLI::Validator finite_number(double min, double max);

/// One of `names`, spelled exactly.
CLI::Validator one_of(const std::vector<std::string>& names);

/// "WxH", each side a whole number in [1, TS_MAX_IMAGE_SIDE].
CLI::Validator image_size();

/// A file name ending in one of `suffixes` (e.g. ".png"); with `also`, those words too.
CLI::Validator file_with_suffix(const std::vector<std::string>& suffixes,
                                const std::vector<std::string>& also = {});

/// A file the command will write: its folder exists and may be written in, and it is not a
/// folder (unwritable_reason, core/image.h). Checked with the command line, so that a mistyped
/// output folder is a bad command line (status 2), found before the work.
CLI::Validator writable_output();

/// A value accepted by `check`, which throws tessera::Error with the reason otherwise; the
/// reason becomes the message. For rules that live with the code they guard (e.g.
/// validate_environment_options), so that the command line cannot drift from them.
CLI::Validator checked_by(std::function<void(const std::string&)> check);

/// Reads "WxH" that image_size() accepted.
std::pair<uint32_t, uint32_t> read_size(const std::string& text);

/// "a, b or c": the words of a message listing choices.
std::string list_of_choices(const std::vector<std::string>& names);

/// Adds `--name CHOICE`, setting `value` to the choice's value. The help shows the choices.
template <class T>
CLI::Option* add_choice(CLI::App& app, const std::string& name, T& value,
                        const std::vector<std::pair<std::string, T>>& choices,
                        const std::string& help) {
  std::vector<std::string> names;
  std::string type;
  for (const auto& choice : choices) {
    names.push_back(choice.first);
    type += (type.empty() ? "" : "|") + choice.first;
  }
  // '_' for '-' as one_of takes it (blinn_phong, the scene files' spelling).
  auto set = [&value, choices](std::string text) {
    std::replace(text.begin(), text.end(), '_', '-');
    for (const auto& [choice, v] : choices) {
      if (choice == text) value = v;
    }
  };
  return app.add_option_function<std::string>(name, set, help)
      ->type_name(type)
      ->check(one_of(names));
}

}  // namespace tessera
