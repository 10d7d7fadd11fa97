#pragma once
// The bad-input corpus convention of tests/data/bad/: each file NAME.EXT that must be refused
// has a sidecar NAME.expected whose first line is a substring the error message must contain;
// the message must also name the file.

#include <functional>
#include <string>

namespace tessera::testing {

/// Runs `error_of` (the message of the Error that loading a path throws, or "" if it loads) on
/// every file in `dir` whose name starts with `prefix` and ends with `extension`, and checks
/// each message as above (GoogleTest failures). Returns the number of files checked.
int expect_bad_corpus(const std::string& dir, const std::string& prefix,
                      const std::string& extension,
                      const std::function<std::string(const std::string&)>& error_of);

}  // namespace tessera::testing
