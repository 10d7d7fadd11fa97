#pragma once
// Embedded SPIR-V of the minimal graphics program's shaders (bench/shaders/), compiled at
// build time.

#include <cstdint>
#include <span>
#include <string_view>

namespace tessera {

/// The SPIR-V words of `bench/shaders/<file>`, named by the file name with '.' as '_'
/// (`minimal_vert`, `minimal_frag`). Static storage; empty when no shader has that name.
std::span<const uint32_t> find_minimal_shader(std::string_view name);

}  // namespace tessera
