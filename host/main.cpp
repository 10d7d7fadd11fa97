// tessera: the command-line tool.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "compute/context.h"
#include "core/builtin_scenes.h"
#include "core/check.h"
#include "host/bench_command.h"
#include "host/cli.h"
#include "host/render_command.h"
#include "host/scene_source.h"

namespace {

int run_devices() {
  for (const tessera::DeviceInfo& d : tessera::list_devices()) {
    std::printf("%u: %s (%s)%s%s\n", d.index, d.name.c_str(), tessera::device_type_name(d.type),
                d.missing.empty() ? "" : " - unusable, lacks: ", d.missing.c_str());
  }
  return 0;
}

int run_scenes() {
  std::fputs(tessera::scene_listing().c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::fputs(tessera::main_help().c_str(), args.empty() ? stderr : stdout);
      return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    if (command == "render") {
      tessera::RenderArgs render;
      if (!tessera::parse_render_args(args, render)) {
        std::fputs(tessera::render_help().c_str(), stdout);
        return 0;
      }
      return tessera::run_render(render);
    }
    if (command == "bench") {
      tessera::BenchArgs bench;
      if (!tessera::parse_bench_args(args, bench)) {
        std::fputs(tessera::bench_help().c_str(), stdout);
        return 0;
      }
      std::string command_line = "tessera";
      for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];
      return tessera::run_bench(bench, command_line);
    }
    if (command == "devices") return run_devices();
    if (command == "scenes") return run_scenes();
    std::fprintf(stderr, "tessera: unknown command '%s'\n\n%s", command.c_str(),
                 tessera::main_help().c_str());
    return 2;
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "tessera: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera: unexpected error: %s\n", e.what());
    return 1;
  }
}
