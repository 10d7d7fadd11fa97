// libFuzzer target: load_scene_text on any text (Tessera's JSON scene format). Files the scene
// names are looked up in the scratch folder, which holds only fuzz.bin. Every input must either
// load or throw tessera::Error. docs/fuzzing.md says how to run it.
#include <cstdint>
#include <string>

#include "core/check.h"
#include "core/scene_file.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tessera::SceneFileOptions options;
  options.max_file_bytes = tessera::fuzz::kMaxFileBytes;
  options.max_model_bytes = tessera::fuzz::kMaxFileBytes;
  options.max_texture_side = tessera::fuzz::kMaxTextureSide;
  // Bounds what instancing generators and built-in shapes may ask for (the defaults allow
  // 2^24 objects and 2^26 vertices, gigabytes, which a user may mean but a fuzzer must not).
  options.max_objects = 1u << 12;
  options.max_mesh_vertices = 1u << 16;
  try {
    tessera::load_scene_text(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json",
                             tessera::fuzz::scratch_dir(), options);
  } catch (const tessera::Error&) {
  }
  return 0;
}
