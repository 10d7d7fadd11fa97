#pragma once
// The reporting half of `tessera bench`: the table on stdout and the CSV, JSON and chart files,
// all from the rows host/bench_measure.h produced.

#include <string>

#include "host/bench_measure.h"
#include "host/cli.h"

namespace tessera {

/// Prints the sweep's settings, one line per row and the compute / hardware ratios: the heading,
/// the rows and the ratios below, which `tessera bench` prints as the sweep goes.
void print_bench_table(const BenchResults& results, const BenchArgs& args);
void print_bench_heading(const std::string& device, const std::string& driver,
                         const BenchArgs& args);
/// One point's line; a point an interruption left with fewer runs than --runs says so.
void print_bench_row(const BenchRow& row, const BenchArgs& args);
void print_bench_ratios(const BenchResults& results);

/// Write the files --csv, --json and --chart name (each only when named). Throw Error if a
/// file cannot be written. `command_line` is recorded in the JSON.
void write_bench_csv(const std::string& path, const BenchResults& results, const BenchArgs& args);
void write_bench_json(const std::string& path, const BenchResults& results, const BenchArgs& args,
                      const std::string& command_line);
void write_bench_chart(const std::string& path, const BenchResults& results, const BenchArgs& args);

}  // namespace tessera
