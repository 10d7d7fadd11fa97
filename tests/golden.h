#pragma once
// The golden check of tests/golden_test.cpp, for other tests that must give the same bits.

#include <string>

#include "compute/renderer.h"

namespace tessera::test {

/// Compares the frame `renderer` last rendered with tests/golden/NAME.png (display image,
/// exactly) and NAME.hash (the HDR image and visibility buffer): GoogleTest failures.
void expect_golden(Renderer& renderer, const std::string& name);

}  // namespace tessera::test
