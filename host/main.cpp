// tessera: the command-line tool. Every failure is reported as one line, "tessera: error: ...",
// with the exit statuses of host/cli.h.
#include <cerrno>
#include <cstdio>
#include <cstring>
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
#include "host/tradeoff.h"
#include "host/view_command.h"

namespace {

// The CPU reference renderer is no Vulkan device, but `render --device` takes it too.
constexpr const char* kReferenceLine =
    "reference: the CPU reference renderer, double precision, no Vulkan (`render --device "
    "reference`, `bench --backends reference`)";

int run_devices() {
  const std::vector<tessera::DeviceInfo> devices = tessera::list_devices();
  if (devices.empty()) {
    std::puts("no Vulkan device found (for the CPU driver: Debian package mesa-vulkan-drivers)");
    std::puts(kReferenceLine);
    return 1;
  }
  for (const tessera::DeviceInfo& d : devices) {
    std::string verdict = d.missing.empty() ? "usable" : "unusable, lacks: " + d.missing;
    std::string how = "--device " + std::to_string(d.index);
    if (d.is_lavapipe) how += " or --device lavapipe";
    if (d.is_default) how += "; the default";
    std::printf("%u: %s (%s) - %s%s%s\n", d.index, d.name.c_str(),
                tessera::device_type_name(d.type), verdict.c_str(), d.missing.empty() ? " (" : "",
                d.missing.empty() ? (how + ")").c_str() : "");
  }
  std::puts(kReferenceLine);
  return 0;
}

int run_scenes() {
  std::fputs(tessera::scene_listing().c_str(), stdout);
  return 0;
}

int run(const tessera::CommandLine& line, const std::string& command_line) {
  switch (line.command) {
    case tessera::Command::help:
      std::fputs(line.help.c_str(), stdout);
      return 0;
    case tessera::Command::render:
      return tessera::run_render(line.render);
    case tessera::Command::bench:
      return tessera::run_bench(line.bench, command_line);
    case tessera::Command::view:
      return tessera::run_view(line.view);
    case tessera::Command::tradeoff:
      return tessera::run_tradeoff(line.tradeoff, command_line);
    case tessera::Command::devices:
      return run_devices();
    case tessera::Command::scenes:
      return run_scenes();
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Each line reaches a log file or a pipe when it is printed (a bench row as its point is
  // measured), not when a buffer fills or the command ends.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::vector<std::string> args(argv + 1, argv + argc);
  std::string command_line = "tessera";
  for (const std::string& arg : args) command_line += " " + arg;
  try {
    const int status = run(tessera::parse_command_line(args), command_line);
    // A full disk or a closed pipe loses what was printed (a table, --version): a failure,
    // not a success with nothing written.
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
      std::fprintf(stderr, "tessera: error: cannot write the standard output: %s\n",
                   std::strerror(errno));
      return status != 0 ? status : tessera::kExitRuntimeError;
    }
    return status;
  } catch (const tessera::UsageError& e) {
    std::fprintf(stderr, "tessera: error: %s\nRun '%s' for the options.\n", e.what(),
                 e.help_command.c_str());
    return tessera::kExitUsageError;
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "tessera: error: %s\n", e.what());
    return tessera::kExitRuntimeError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera: error: unexpected: %s\n", e.what());
    return tessera::kExitRuntimeError;
  }
}
