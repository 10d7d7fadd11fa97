#include "fuzz/fuzz_support.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace tessera::fuzz {

namespace fs = std::filesystem;

namespace {

fs::path make_scratch_dir() {
  std::error_code ec;
  const char* chosen = std::getenv("TESSERA_FUZZ_SCRATCH");
  const fs::path root = chosen                             ? fs::path(chosen)
                        : fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm")
                                                           : fs::temp_directory_path();
  const fs::path dir = root / ("tessera-fuzz-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream bin(dir / "fuzz.bin", std::ios::binary);
  for (int i = 0; i < 256; ++i) bin.put(char(i));
  std::atexit([] {
    std::error_code ignored;
    fs::remove_all(scratch_dir(), ignored);
  });
  return dir;
}

}  // namespace

const std::string& scratch_dir() {
  // Never destroyed: the atexit handler that removes the folder runs after static destructors.
  static const std::string* dir = new std::string(make_scratch_dir().string());
  return *dir;
}

void write_scratch(const std::string& name, const uint8_t* bytes, size_t size) {
  std::ofstream out(fs::path(scratch_dir()) / name, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes), std::streamsize(size));
}

}  // namespace tessera::fuzz
