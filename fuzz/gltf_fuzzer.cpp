// libFuzzer target: import_gltf_bytes on any bytes (a .gltf's JSON or a whole .glb). Every input
// must either import or throw tessera::Error; anything else (a crash, a sanitizer report, an
// internal check, another exception) is a bug. docs/fuzzing.md says how to run it.
#include <cstdint>
#include <vector>

#include "core/check.h"
#include "core/model_import.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tessera::ImportOptions options;
  options.max_file_bytes = tessera::fuzz::kMaxFileBytes;
  options.max_texture_side = tessera::fuzz::kMaxTextureSide;
  const std::vector<unsigned char> bytes(data, data + size);
  try {
    tessera::import_gltf_bytes(bytes, "fuzz.gltf", tessera::fuzz::scratch_dir(), options);
  } catch (const tessera::Error&) {
  }
  return 0;
}
