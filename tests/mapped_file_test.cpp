// map_file (core/mapped_file.h): a file's bytes mapped, or read where it cannot be mapped, and
// the errors for files that cannot be read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/check.h"
#include "core/mapped_file.h"

namespace tessera {
namespace {

std::filesystem::path temp_file(const std::string& name, const std::string& content) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("tessera_mapped_file_" + name);
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

std::string text(const MappedFile& file) {
  return std::string(reinterpret_cast<const char*>(file.data()), file.size());
}

std::string error_of(const std::string& path, uint64_t max_bytes) {
  try {
    map_file(path, max_bytes);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(MappedFile, HoldsTheFilesBytes) {
  std::string content(100000, '\0');
  for (size_t i = 0; i < content.size(); ++i) content[i] = char(i * 7 + i / 251);
  const auto path = temp_file("bytes", content);
  const MappedFile file = map_file(path.string(), content.size());
  EXPECT_EQ(text(file), content);
}

TEST(MappedFile, EmptyFileHasNoBytes) {
  const auto path = temp_file("empty", "");
  const MappedFile file = map_file(path.string(), 10);
  EXPECT_EQ(file.size(), 0u);
}

// procfs files have no size (st_size 0) and cannot be mapped: they are read to the end.
TEST(MappedFile, FilesWithoutASizeAreRead) {
  const MappedFile file = map_file("/proc/self/status", 1 << 20);
  EXPECT_NE(text(file).find("VmRSS"), std::string::npos) << text(file);
}

TEST(MappedFile, MovedFromHoldsNothing) {
  const auto path = temp_file("moved", "glTF bytes");
  MappedFile a = map_file(path.string(), 100);
  MappedFile b = std::move(a);
  EXPECT_EQ(a.size(), 0u);
  EXPECT_EQ(a.data(), nullptr);
  EXPECT_EQ(text(b), "glTF bytes");
  b = map_file(temp_file("moved2", "other").string(), 100);
  EXPECT_EQ(text(b), "other");
}

TEST(MappedFile, ErrorsNameTheFileAndTheProblem) {
  const std::string missing =
      (std::filesystem::temp_directory_path() / "tessera_mapped_file_none").string();
  EXPECT_EQ(error_of(missing, 100), missing + ": cannot read the file: No such file or directory");
  const std::string dir = std::filesystem::temp_directory_path().string();
  EXPECT_EQ(error_of(dir, 100), dir + ": cannot read the file: Is a directory");
  const std::string big = temp_file("big", std::string(101, 'x')).string();
  EXPECT_EQ(error_of(big, 100), big + ": is 101 bytes, over the limit of 100");
  EXPECT_EQ(error_of("/proc/self/status", 10), "/proc/self/status: is over the limit of 10 bytes");
}

}  // namespace
}  // namespace tessera
