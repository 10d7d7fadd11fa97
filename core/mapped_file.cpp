#include "core/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>
#include <vector>

#include "core/check.h"

namespace tessera {
namespace {

[[noreturn]] void cannot_read(const std::string& path, int error) {
  throw Error(path + ": cannot read the file: " + std::strerror(error));
}

[[noreturn]] void not_regular(const std::string& path, mode_t mode) {
  const char* kind = S_ISDIR(mode)    ? "a directory"
                     : S_ISFIFO(mode) ? "a FIFO"
                     : S_ISCHR(mode)  ? "a character device"
                     : S_ISBLK(mode)  ? "a block device"
                     : S_ISSOCK(mode) ? "a socket"
                                      : "a special file";
  throw Error(path + ": is not a regular file (" + kind + ")");
}

// Closes a file descriptor on every way out of map_file.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

MappedFile::MappedFile(MappedFile&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      mapped_(std::exchange(other.mapped_, false)),
      read_(std::move(other.read_)) {}  // a vector's move keeps its bytes where data_ points

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    release();
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, false);
    read_ = std::move(other.read_);
  }
  return *this;
}

MappedFile::~MappedFile() {
  release();
}

void MappedFile::release_pages(size_t offset, size_t size) {
  TESSERA_CHECK(offset <= size_ && size <= size_ - offset);
  if (!mapped_) return;
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  const size_t first = (offset + page - 1) / page * page, end = (offset + size) / page * page;
  // A hint: where the kernel refuses, the pages stay resident, which costs memory, not bytes.
  if (first < end) ::madvise(data_ + first, end - first, MADV_DONTNEED);
}

void ReadPages::mark_read(const unsigned char* begin, size_t size) {
  // Compared as addresses: `begin` may point into another object.
  const uintptr_t data = reinterpret_cast<uintptr_t>(file_.data()),
                  at = reinterpret_cast<uintptr_t>(begin);
  if (!file_.mapped() || size == 0 || at < data || at - data > file_.size() ||
      size > file_.size() - (at - data)) {
    return;
  }
  size_t first = at - data, end = first + size;
  // The ranges that touch this one merge into it; their whole pages were released before.
  std::vector<std::pair<size_t, size_t>> merged;
  auto it = read_.upper_bound(first);
  if (it != read_.begin() && std::prev(it)->second >= first) --it;
  while (it != read_.end() && it->first <= end) {
    merged.push_back(*it);
    first = std::min(first, it->first);
    end = std::max(end, it->second);
    it = read_.erase(it);
  }
  read_.emplace(first, end);
  // The whole pages of the merged range, less those of the ranges merged into it.
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  const auto whole = [page](size_t a, size_t b) {
    const size_t low = (a + page - 1) / page * page, high = b / page * page;
    return std::pair(low, std::max(low, high));
  };
  size_t cursor = whole(first, end).first;
  const size_t last = whole(first, end).second;
  for (const auto& [a, b] : merged) {
    const auto [done_first, done_end] = whole(a, b);
    if (done_first >= done_end) continue;
    if (done_first > cursor) release(cursor, std::min(done_first, last) - cursor);
    cursor = std::max(cursor, done_end);
  }
  if (cursor < last) release(cursor, last - cursor);
}

void ReadPages::release(size_t offset, size_t size) {
  // Pages are queued once each (mark_read), so the queued ranges never overlap; touching
  // ones merge, so that a batch of adjacent pages is one call.
  size_t first = offset, end = offset + size;
  auto it = pending_.upper_bound(first);
  if (it != pending_.begin() && std::prev(it)->second == first) --it;
  while (it != pending_.end() && it->first <= end) {
    first = std::min(first, it->first);
    end = std::max(end, it->second);
    it = pending_.erase(it);
  }
  pending_.emplace(first, end);
  pending_bytes_ += size;
  if (pending_bytes_ < batch_bytes_) return;
  for (const auto& [a, b] : pending_) file_.release_pages(a, b - a);
  pending_.clear();
  pending_bytes_ = 0;
}

void MappedFile::release() {
  if (mapped_) ::munmap(data_, size_);
  read_ = {};
  data_ = nullptr;
  size_ = 0;
  mapped_ = false;
}

void require_regular_file(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode)) {
    not_regular(path, status.st_mode);
  }
}

MappedFile map_file(const std::string& path, uint64_t max_bytes) {
  // Before opening: opening a FIFO would block.
  require_regular_file(path);
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) cannot_read(path, errno);
  struct stat status {};
  if (::fstat(file.fd, &status) != 0) cannot_read(path, errno);
  // What was opened, should the path have been replaced since.
  if (!S_ISREG(status.st_mode)) not_regular(path, status.st_mode);
  MappedFile out;
  if (status.st_size > 0) {
    if (uint64_t(status.st_size) > max_bytes) {
      throw Error(path + ": is " + std::to_string(status.st_size) + " bytes, over the limit of " +
                  std::to_string(max_bytes));
    }
    void* p =
        ::mmap(nullptr, size_t(status.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, file.fd, 0);
    if (p != MAP_FAILED) {
      out.data_ = static_cast<unsigned char*>(p);
      out.size_ = size_t(status.st_size);
      out.mapped_ = true;
      return out;
    }
  }
  // Not mappable: read to the end, whatever the size fstat gave (a procfs file's is 0).
  unsigned char chunk[1 << 16];
  for (;;) {
    const ssize_t got = ::read(file.fd, chunk, sizeof chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) cannot_read(path, errno);
    if (got == 0) break;
    if (out.read_.size() + size_t(got) > max_bytes) {
      throw Error(path + ": is over the limit of " + std::to_string(max_bytes) + " bytes");
    }
    out.read_.insert(out.read_.end(), chunk, chunk + got);
  }
  out.data_ = out.read_.empty() ? nullptr : out.read_.data();
  out.size_ = out.read_.size();
  return out;
}

}  // namespace tessera
