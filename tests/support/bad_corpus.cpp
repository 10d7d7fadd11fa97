#include "tests/support/bad_corpus.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace tessera::testing {

int expect_bad_corpus(const std::string& dir, const std::string& prefix,
                      const std::string& extension,
                      const std::function<std::string(const std::string&)>& error_of) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != extension || name.rfind(prefix, 0) != 0) continue;
    std::ifstream in(std::filesystem::path(entry.path()).replace_extension(".expected"));
    std::string expected;
    EXPECT_TRUE(std::getline(in, expected)) << entry.path() << " has no .expected file";
    const std::string message = error_of(entry.path().string());
    EXPECT_NE(message.find(expected), std::string::npos)
        << entry.path() << ": expected '" << expected << "', got: " << message;
    EXPECT_NE(message.find(name), std::string::npos) << message;
    ++files;
  }
  return files;
}

}  // namespace tessera::testing
