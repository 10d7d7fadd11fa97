// Renders Tessera's default scene (the 7x7 sphere grid) to a PNG.
//   render_spheres [OUT.png [DEVICE]]   DEVICE: auto (default), lavapipe, gpu or an index
#include <cstdio>
#include <string>

#include "compute/renderer.h"
#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/image.h"

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "spheres.png";
  const std::string device = argc > 2 ? argv[2] : "auto";
  try {
    auto ctx = tessera::create_context({.device = device});
    tessera::Renderer renderer(*ctx);
    renderer.set_scene(tessera::make_sphere_grid_scene());
    const tessera::FrameStats stats = renderer.render({.width = 512, .height = 512});
    tessera::write_png(out, renderer.read_ldr());
    std::printf("%s: %llu triangles on %s, %.2f ms on the GPU\n", out.c_str(),
                static_cast<unsigned long long>(stats.raster_triangles), ctx->properties.deviceName,
                stats.gpu_total_ms);
    return 0;
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "render_spheres: %s\n", e.what());
    return 1;
  }
}
