#pragma once
// A file's bytes in memory, read-only, for importers that parse a whole file at once.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tessera {

/// The bytes of a file, mapped read-only (POSIX mmap with MAP_POPULATE): the page cache's own
/// pages, mapped in one call, where reading into a buffer costs fresh pages (a page fault each
/// 4 KiB) and a copy of every byte. That was a fifth of a 1.8 MB glb's import
/// (docs/performance.md, "Loading speed"). Regular files that cannot be mapped (empty ones,
/// procfs files, whose size reads 0) are read into memory instead; anything else is refused
/// (require_regular_file). Move-only; unmaps on destruction.
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
  /// Whether the bytes are the file's mapping (not a copy read into memory).
  bool mapped() const { return mapped_; }

  /// Gives back the pages that lie wholly inside bytes [offset, offset + size) of a mapped file
  /// (madvise MADV_DONTNEED, POSIX_MADV_DONTNEED's Linux form): they leave the process's
  /// resident memory, and reading them again maps them again from the page cache, the same
  /// bytes (the mapping is private and never written). Does nothing for a file that was read.
  /// Requires offset + size <= size().
  void release_pages(size_t offset, size_t size);

 private:
  friend MappedFile map_file(const std::string& path, uint64_t max_bytes);
  void release();
  unsigned char* data_ = nullptr;  // the mapping, or read_'s bytes
  size_t size_ = 0;
  bool mapped_ = false;
  std::vector<unsigned char> read_;  // a file that could not be mapped
};

/// Releases a mapped file's pages once every byte on them has been read, so that a file read
/// once, front to back or in any order, is not all resident at the end of the reading (an
/// importer's meshes and the file they came from, held at once, were more than twice the file's
/// vertex data). mark_read records a range as read and releases (MappedFile::release_pages) the
/// pages that the ranges read so far now cover wholly; a page is released once. Releases go
/// out in batches of at least `batch_bytes`, adjacent pages in one call: on the development VM
/// (a paravirtualized guest) releasing a 1.8 MB glb accessor by accessor, about 50 calls, took
/// its import from 2.3 to 4.1 ms where the heap was warm, and one call at the end 2.3 ms
/// (docs/performance.md, "Loading speed"). Up to `batch_bytes` of read pages may stay resident.
/// Reading a released page again is correct, and costs a page fault. Does nothing for a file
/// that was read into memory. Holds `file` by reference: it must outlive this.
class ReadPages {
 public:
  explicit ReadPages(MappedFile& file, size_t batch_bytes = size_t(64) << 10)
      : file_(file), batch_bytes_(batch_bytes) {}
  /// Records bytes [begin, begin + size) as read; a range outside the file is ignored.
  void mark_read(const unsigned char* begin, size_t size);

 private:
  void release(size_t offset, size_t size);  // queued, then given back in a batch
  MappedFile& file_;
  size_t batch_bytes_;
  std::map<size_t, size_t> read_;     // the ranges read, merged: first byte -> one past the last
  std::map<size_t, size_t> pending_;  // whole pages to release, merged likewise
  size_t pending_bytes_ = 0;
};

/// Maps (or reads) the file at `path`. Throws tessera::Error "PATH: cannot read the file: REASON"
/// if it cannot be opened or read, require_regular_file's error for what is not a regular file,
/// and "PATH: is N bytes, over the limit of MAX_BYTES" for a larger file, checked before any byte
/// is read.
MappedFile map_file(const std::string& path, uint64_t max_bytes);

/// Throws tessera::Error "PATH: is not a regular file (a directory)" (a FIFO, a character device,
/// a block device, a socket) where `path` names something that exists and is not a regular file,
/// symbolic links followed; does nothing otherwise (a missing file is left to the caller, whose
/// message says where the name came from). Loaders call it (map_file does) before they measure
/// or open a file they are given: opening a FIFO blocks until a writer comes, /dev/zero never
/// ends, and std::filesystem::file_size reports either as "Operation not supported" (a fresh
/// user's trial).
void require_regular_file(const std::string& path);

}  // namespace tessera
