// map_file (core/mapped_file.h): a file's bytes mapped, or read where it cannot be mapped, and
// the errors for files that cannot be read; ReadPages, which gives back the pages read;
// require_regular_file, through every loader.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include "core/check.h"
#include "core/environment.h"
#include "core/mapped_file.h"
#include "core/model_import.h"
#include "core/scene_file.h"
#include "core/texture.h"
#include "host/view_script.h"

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

// Whether each page of `file` is mapped in this process: bit 63 of its /proc/self/pagemap entry
// (Linux's documented page map, readable for one's own process).
std::vector<bool> present_pages(const MappedFile& file) {
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  const int fd = open("/proc/self/pagemap", O_RDONLY);
  std::vector<bool> present;
  for (size_t offset = 0; offset < file.size(); offset += page) {
    uint64_t entry = 0;
    const off_t at = off_t((reinterpret_cast<uintptr_t>(file.data()) + offset) / page * 8);
    EXPECT_EQ(pread(fd, &entry, 8, at), 8);
    present.push_back((entry >> 63) & 1);
  }
  close(fd);
  return present;
}

// Pages leave the process once the ranges read cover them wholly, in whatever order and
// pieces they were read; what is read again afterwards is the same bytes.
TEST(ReadPages, ReleasesThePagesThatReadRangesCoverWholly) {
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  std::string content(8 * page + 100, '\0');
  for (size_t i = 0; i < content.size(); ++i) content[i] = char(i * 13 + i / 4093);
  const auto path = temp_file("pages", content);
  MappedFile file = map_file(path.string(), content.size());
  ASSERT_TRUE(file.mapped());
  EXPECT_EQ(present_pages(file), std::vector<bool>(9, true));  // MAP_POPULATE
  ReadPages pages(file, 0);                                    // each release at once
  const unsigned char* d = file.data();
  pages.mark_read(d + 100, 2 * page);  // bytes 100 .. 2 pages + 100: only page 1 is whole
  EXPECT_EQ(present_pages(file),
            (std::vector<bool>{true, false, true, true, true, true, true, true, true}));
  pages.mark_read(d + 5 * page, page + 1);  // page 5 whole, page 6 only begun
  EXPECT_EQ(present_pages(file),
            (std::vector<bool>{true, false, true, true, true, false, true, true, true}));
  // The first 100 bytes complete page 0; the range between the two read ones completes pages
  // 2 to 4 (the one read range that merges them all).
  pages.mark_read(d, 100);
  pages.mark_read(d + 2 * page + 100, 3 * page - 100);
  EXPECT_EQ(present_pages(file),
            (std::vector<bool>{false, false, false, false, false, false, true, true, true}));
  // The rest, read again from its start: the last page (100 bytes of it in the file) stays.
  pages.mark_read(d + 6 * page - 10, 2 * page + 110);
  EXPECT_EQ(present_pages(file),
            (std::vector<bool>{false, false, false, false, false, false, false, false, true}));
  // A range outside the file is ignored; released pages read back as the file's bytes.
  const unsigned char elsewhere[2] = {};
  pages.mark_read(elsewhere, 2);
  EXPECT_EQ(text(file), content);
}

// Releases wait until a batch's worth of pages is read, then go out together.
TEST(ReadPages, ReleasesInBatches) {
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  const auto path = temp_file("batches", std::string(8 * page, 'b'));
  MappedFile file = map_file(path.string(), 8 * page);
  ReadPages pages(file, 3 * page);
  const unsigned char* d = file.data();
  pages.mark_read(d + 4 * page, 2 * page);  // pages 4 and 5, queued
  EXPECT_EQ(present_pages(file), std::vector<bool>(8, true));
  pages.mark_read(d, page);  // a third page: the batch goes out
  EXPECT_EQ(present_pages(file),
            (std::vector<bool>{false, true, true, true, false, false, true, true}));
  pages.mark_read(d + page, 3 * page);  // pages 1 to 3: a batch at once
  EXPECT_EQ(present_pages(file),
            (std::vector<bool>{false, false, false, false, false, false, true, true}));
  EXPECT_EQ(text(file), std::string(8 * page, 'b'));
}

// A file that was read, not mapped, keeps its bytes.
TEST(ReadPages, LeavesAFileReadIntoMemoryAlone) {
  MappedFile file = map_file("/proc/self/status", 1 << 20);
  ASSERT_FALSE(file.mapped());
  const std::string before = text(file);
  ReadPages pages(file);
  pages.mark_read(file.data(), file.size());
  EXPECT_EQ(text(file), before);
}

TEST(MappedFile, ErrorsNameTheFileAndTheProblem) {
  const std::string missing =
      (std::filesystem::temp_directory_path() / "tessera_mapped_file_none").string();
  EXPECT_EQ(error_of(missing, 100), missing + ": cannot read the file: No such file or directory");
  const std::string dir = std::filesystem::temp_directory_path().string();
  EXPECT_EQ(error_of(dir, 100), dir + ": is not a regular file (a directory)");
  const std::string big = temp_file("big", std::string(101, 'x')).string();
  EXPECT_EQ(error_of(big, 100), big + ": is 101 bytes, over the limit of 100");
  EXPECT_EQ(error_of("/proc/self/status", 10), "/proc/self/status: is over the limit of 10 bytes");
}

// What is not a regular file is refused by name before it is opened (a fresh user's trial got
// "Operation not supported"): /dev/zero would be read until the limit, and opening a FIFO
// would block until something writes to it.
TEST(MappedFile, RefusesWhatIsNotARegularFile) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  ASSERT_EQ(error_of(dir, 100), dir + ": is not a regular file (a directory)");
  ASSERT_EQ(error_of("/dev/zero", 100), "/dev/zero: is not a regular file (a character device)");
  const std::string fifo =
      (std::filesystem::temp_directory_path() / "tessera_mapped_fifo").string();
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(error_of(fifo, 100), fifo + ": is not a regular file (a FIFO)");
  std::filesystem::remove(fifo);
}

std::string load_error(const std::function<void()>& load) {
  try {
    load();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// load_error of `load`, which opens the FIFO `fifo`: a writer comes and goes (a thread opens it
// without blocking, as often as a reader has it open, and closes it at once), so that a loader
// that opens it reads an empty file and fails, instead of blocking the test for ever.
std::string fifo_load_error(const std::string& fifo, const std::function<void()>& load) {
  std::atomic<bool> done = false;
  std::thread writer([&] {
    while (!done) {
      const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // ENXIO while none reads
      if (fd >= 0) ::close(fd);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  const std::string error = load_error(load);
  done = true;
  writer.join();
  return error;
}

// An environment map (render --env, a scene file's environment) and a view script (view
// --script) are checked as the loaders below are: a FIFO blocked the open until a writer came.
TEST(MappedFile, EnvironmentAndViewScriptRefuseWhatIsNotARegularFile) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "tessera_env_fifo";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "folder.hdr");
  const std::string d = dir.string() + "/";
  EXPECT_EQ(load_error([&] { load_environment(d + "folder.hdr"); }),
            d + "folder.hdr: is not a regular file (a directory)");
  EXPECT_EQ(load_error([&] { load_view_script(d + "folder.hdr"); }),
            d + "folder.hdr: is not a regular file (a directory)");
  for (const char* name : {"sky.hdr", "sky.pfm", "script.txt"}) {
    ASSERT_EQ(mkfifo((d + name).c_str(), 0600), 0);
  }
  for (const char* name : {"sky.hdr", "sky.pfm"}) {
    EXPECT_EQ(fifo_load_error(d + name, [&] { load_environment(d + name); }),
              d + name + ": is not a regular file (a FIFO)");
  }
  EXPECT_EQ(fifo_load_error(d + "script.txt", [&] { load_view_script(d + "script.txt"); }),
            d + "script.txt: is not a regular file (a FIFO)");
  std::filesystem::remove_all(dir);
}

// Every loader of a file it is given checks it with require_regular_file: models (glTF and the
// buffers it names, OBJ and its material libraries), textures, scene files and the files they
// name. Each says PATH: is not a regular file (WHAT), after the place the name came from.
TEST(MappedFile, EveryLoaderRefusesWhatIsNotARegularFile) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "tessera_not_regular";
  std::filesystem::remove_all(dir);
  for (const char* folder : {"folder.gltf", "folder.obj", "folder.mtl", "folder.bin"}) {
    std::filesystem::create_directories(dir / folder);
  }
  const std::string d = dir.string() + "/";
  // Directories first: before the check each of these gave another message, and a FIFO below
  // would have blocked the loaders that open it.
  ASSERT_EQ(load_error([&] { import_gltf(d + "folder.gltf"); }),
            d + "folder.gltf: is not a regular file (a directory)");
  ASSERT_EQ(load_error([&] { import_obj(d + "folder.obj"); }),
            d + "folder.obj: is not a regular file (a directory)");
  ASSERT_EQ(load_error([&] { load_texture(d + "folder.gltf", true); }),
            d + "folder.gltf: is not a regular file (a directory)");
  ASSERT_EQ(load_error([&] { load_scene_file(d + "folder.gltf"); }),
            d + "folder.gltf: is not a regular file (a directory)");
  std::ofstream(d + "buffer.gltf")
      << R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4, "uri": "folder.bin"}]})";
  ASSERT_EQ(
      load_error([&] { import_gltf(d + "buffer.gltf"); }),
      d + "buffer.gltf: buffers[0].uri: " + d + "folder.bin: is not a regular file (a directory)");
  std::ofstream(d + "library.obj") << "mtllib folder.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  ASSERT_EQ(load_error([&] { import_obj(d + "library.obj"); }),
            "'" + d + "library.obj' line 1: material library " + d +
                "folder.mtl: is not a regular file (a directory)");
  const std::string fifo = d + "fifo.gltf";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string refused = fifo + ": is not a regular file (a FIFO)";
  EXPECT_EQ(load_error([&] { import_gltf(fifo); }), refused);
  EXPECT_EQ(load_error([&] { import_obj(fifo); }), refused);
  EXPECT_EQ(load_error([&] { load_texture(fifo, true); }), refused);
  EXPECT_EQ(load_error([&] { load_scene_file(fifo); }), refused);
  // A scene file's model and texture, after the place that names them (columns 35 and 53: the
  // opening quote of each file's name).
  EXPECT_EQ(load_error([&] {
              load_scene_text(R"({"models": [{"name": "m", "file": "fifo.gltf"}], )"
                              R"("objects": [{"model": "m"}]})",
                              "s.json", dir.string());
            }),
            "s.json:1:35: models.m.file: " + refused);
  EXPECT_EQ(load_error([&] {
              load_scene_text(
                  R"({"textures": [{"name": "t", "type": "file", "file": "fifo.gltf"}]})", "t.json",
                  dir.string());
            }),
            "t.json:1:53: textures.t.file: " + refused);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera
