#pragma once
// What the loader fuzzers (fuzz/*_fuzzer.cpp) share: the folder that files named by a fuzzed
// input resolve against, and limits that keep one input within libFuzzer's memory limit.
#include <cstdint>
#include <string>

namespace tessera::fuzz {

/// A folder of this process in $TESSERA_FUZZ_SCRATCH (scripts/fuzz.sh sets it, and removes it
/// with what crashed runs leave), else /dev/shm or $TMPDIR, created on first
/// use and holding one small file, "fuzz.bin" (256 bytes 0..255), for inputs that name an
/// external buffer or image. Removed at exit.
const std::string& scratch_dir();

/// Writes `bytes` to scratch_dir()/name, replacing what was there.
void write_scratch(const std::string& name, const uint8_t* bytes, size_t size);

/// Size limits for fuzzed imports: files (and buffers) up to 1 MiB, textures up to 256 texels a
/// side, so no input asks for more than a few MiB however large it says its data is.
constexpr uint64_t kMaxFileBytes = 1u << 20;
constexpr uint32_t kMaxTextureSide = 256;

}  // namespace tessera::fuzz
