#pragma once

#include "host/cli.h"

namespace tessera {

/// Runs `tessera view` with parsed arguments until the window is closed or the script exits;
/// returns the process exit code (kExitValidationError with --validate and reports).
/// Throws tessera::Error for bad input, no display, or device problems.
int run_view(const ViewArgs& args);

}  // namespace tessera
