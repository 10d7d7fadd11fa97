#pragma once
// Embedded SPIR-V of every compute shader of the renderer, compiled at build time from
// shaders/*.comp (all of them: shaders/CMakeLists.txt finds them without a list).

#include <cstdint>
#include <span>
#include <string_view>

namespace tessera {

/// Returns the SPIR-V words of the shader compiled from `shaders/<name>.comp`, or of a variant
/// of one compiled with a preprocessor definition (shaders/CMakeLists.txt's VARIANTS, such as
/// `shade_untextured`).
/// The span points into static storage owned by the library (valid for the program's life).
/// Returns an empty span when no shader has that name.
std::span<const uint32_t> find_shader(std::string_view name);

}  // namespace tessera
