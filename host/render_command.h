#pragma once

#include "host/cli.h"

namespace tessera {

/// Runs `tessera render` with parsed arguments; returns the process exit code.
/// Throws tessera::Error for bad input (unknown scene, unwritable path, device problems).
int run_render(const RenderArgs& args);

}  // namespace tessera
