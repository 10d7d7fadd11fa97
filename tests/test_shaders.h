#pragma once
// Embedded SPIR-V of the shaders only tests dispatch (tests/shaders/), compiled at build time.

#include <cstdint>
#include <span>
#include <string_view>

namespace tessera {

/// The SPIR-V words of `tests/shaders/<file>`, named by the file name without ".comp"
/// (`wait_for_host`). Static storage; empty when no shader has that name.
std::span<const uint32_t> find_test_shader(std::string_view name);

}  // namespace tessera
