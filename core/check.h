#pragma once
// Two kinds of failure, kept apart (as in pbrt-v4):
// - TESSERA_CHECK: an invariant of Tessera's own code. Failing it is a bug; it stays on in
//   release builds, prints the source file and line, and aborts.
// - tessera::Error: bad input from a user (arguments, scenes, meshes, sizes, devices). It is
//   thrown with a message that names the problem and is shown to the user as it is.

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace tessera {

struct Error : std::runtime_error {
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

[[noreturn]] inline void check_failed(const char* expr, const char* file, int line) {
  std::fprintf(stderr, "tessera: internal check failed: %s (%s:%d)\n", expr, file, line);
  std::abort();
}

}  // namespace tessera

#define TESSERA_CHECK(expr) \
  ((expr) ? static_cast<void>(0) : ::tessera::check_failed(#expr, __FILE__, __LINE__))
