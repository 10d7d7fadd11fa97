#pragma once
// `tessera bench`: sweeps a benchmark scene family over object counts and backends.

#include <string>

#include "host/cli.h"

namespace tessera {

/// Runs the sweep, prints a table and writes the requested files; returns the exit status.
/// `command_line` is recorded in the JSON file. Throws Error when an output file cannot be
/// written (checked before measuring) or a device cannot be used.
int run_bench(const BenchArgs& args, const std::string& command_line);

}  // namespace tessera
