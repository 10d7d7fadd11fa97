#pragma once
// A file's bytes in memory, read-only, for importers that parse a whole file at once.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tessera {

/// The bytes of a file, mapped read-only (POSIX mmap with MAP_POPULATE): the page cache's own
/// pages, mapped in one call, where reading into a buffer costs fresh pages (a page fault each
/// 4 KiB) and a copy of every byte. That was a fifth of a 1.8 MB glb's import
/// (docs/performance.md, "Loading speed"). Files that cannot be mapped (empty ones, pipes,
/// special files) are read into memory instead. Move-only; unmaps on destruction.
/// A mapped file that another process truncates while it is mapped raises SIGBUS on reading
/// past its new end, as with any mapped file; importers read their files for milliseconds.
class MappedFile {
 public:
  MappedFile() = default;
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile();

  const unsigned char* data() const { return data_; }
  size_t size() const { return size_; }

 private:
  friend MappedFile map_file(const std::string& path, uint64_t max_bytes);
  void release();
  unsigned char* data_ = nullptr;  // the mapping, or read_'s bytes
  size_t size_ = 0;
  bool mapped_ = false;
  std::vector<unsigned char> read_;  // a file that could not be mapped
};

/// Maps (or reads) the file at `path`. Throws tessera::Error "PATH: cannot read the file: REASON"
/// if it cannot be opened or read, and "PATH: is N bytes, over the limit of MAX_BYTES" for a
/// larger file, checked before any byte is read.
MappedFile map_file(const std::string& path, uint64_t max_bytes);

}  // namespace tessera
