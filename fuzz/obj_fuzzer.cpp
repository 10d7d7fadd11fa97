// libFuzzer target: import_obj_text on any text. A line "#%fuzz.mtl" splits the input: what
// follows it is written to fuzz.mtl in the scratch folder, where "mtllib fuzz.mtl" finds it, so
// material libraries are fuzzed with the OBJ that uses them. Every input must either import or
// throw tessera::Error. docs/fuzzing.md says how to run it.
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/check.h"
#include "core/model_import.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view kSplit = "\n#%fuzz.mtl\n";
  const size_t split = std::min(input.find(kSplit), input.size());
  const std::string_view mtl = input.substr(std::min(split + kSplit.size(), input.size()));
  // Written on every input, so that no input sees the library of the one before.
  tessera::fuzz::write_scratch("fuzz.mtl", reinterpret_cast<const uint8_t*>(mtl.data()),
                               mtl.size());
  tessera::ImportOptions options;
  options.max_file_bytes = tessera::fuzz::kMaxFileBytes;
  options.max_texture_side = tessera::fuzz::kMaxTextureSide;
  try {
    tessera::import_obj_text(std::string(input.substr(0, split)), "fuzz.obj",
                             tessera::fuzz::scratch_dir(), options);
  } catch (const tessera::Error&) {
  }
  return 0;
}
