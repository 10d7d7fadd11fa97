// make_large_obj PATH [TRIANGLES]: writes bench/large_obj.h's grid (default 10^7 triangles),
// for measuring `tessera` loading a large model.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "bench/large_obj.h"

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: make_large_obj PATH [TRIANGLES (default 10000000)]\n");
    return 2;
  }
  try {
    const unsigned long long wanted = argc == 3 ? std::strtoull(argv[2], nullptr, 10) : 10000000ull;
    const unsigned long long n = tessera::bench::write_large_obj(argv[1], wanted);
    std::printf("%s: %llu triangles\n", argv[1], n);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_large_obj: %s\n", e.what());
    return 1;
  }
}
