#pragma once
// The golden check of tests/golden_test.cpp, for other tests that must give the same bits (the
// scene files of scenes/, and the imported models of the glTF and OBJ tests, through
// expect_reference_and_golden in tests/accuracy_support.h).

#include <string>

#include "compute/renderer.h"

namespace tessera::test {

/// Compares the frame `renderer` last rendered with tests/golden/NAME.png (display image,
/// exactly) and NAME.hash (the HDR image and visibility buffer): GoogleTest failures.
void expect_golden(Renderer& renderer, const std::string& name);

}  // namespace tessera::test
