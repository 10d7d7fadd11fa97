#pragma once
// A parallel loop over independent items, for CPU work that scales with the scene (texture
// mip chains, texture decoding).

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tessera {

/// Most threads parallel_for starts (the caller's among them); 0, the default, means one per
/// core. Benchmarks set it to 1 to time the parallel steps against one thread in the same run.
inline std::atomic<unsigned> parallel_thread_limit{0};

/// Calls fn(i) for every i in [0, count) on up to hardware_concurrency threads (the caller's
/// among them), or parallel_thread_limit when it is set; items are handed out one at a time, so
/// uneven items balance. fn must be safe to call concurrently for different i. The first exception
/// thrown by fn is rethrown here after every thread has stopped; items not yet started are then
/// skipped.
template <typename Fn>
void parallel_for(size_t count, Fn&& fn) {
  const unsigned limit = parallel_thread_limit.load();
  const size_t threads =
      std::min<size_t>(count, limit ? limit : std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (size_t i; (i = next.fetch_add(1)) < count;) {
      try {
        fn(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace tessera
