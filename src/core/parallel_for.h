// Minimal parallel loops for independent, coarse jobs (decoding images, building mip chains,
// image metrics). Each job should take milliseconds or more: a thread is started per
// worker for every call, so this is not for fine-grained work.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace bounce {

// Runs job(i) for i in [0, count) on up to hardware_concurrency threads. Jobs are handed out
// one at a time, so uneven jobs (a 4K texture beside a 64x64 one) still balance. After a job
// throws, no new jobs start; the exception of the lowest failing index is rethrown, so which
// error the user sees does not depend on thread timing (jobs start in index order, so every
// job below a failing one has run).
template <typename Job>
void parallelFor(size_t count, const Job& job) {
  size_t workers = std::min<size_t>(count, std::max(1u, std::thread::hardware_concurrency()));
  if (workers <= 1) {
    for (size_t i = 0; i < count; ++i) job(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr firstError;
  size_t firstErrorIndex = count;
  std::mutex errorMutex;
  auto work = [&] {
    for (size_t i = next++; i < count && !failed; i = next++) {
      try {
        job(i);
      } catch (...) {
        std::lock_guard lock(errorMutex);
        if (i < firstErrorIndex) {
          firstErrorIndex = i;
          firstError = std::current_exception();
        }
        failed = true;
      }
    }
  };
  std::vector<std::thread> threads;
  for (size_t w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (firstError) std::rethrow_exception(firstError);
}

// Calls rowBand(begin, end) for disjoint bands covering [0, rows), one band per thread at most.
// Bands of fewer than `minRowsPerBand` rows are not worth a thread.
template <typename RowBand>
void parallelForRows(int rows, const RowBand& rowBand, int minRowsPerBand = 32) {
  const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
  const int bands = std::clamp(rows / std::max(1, minRowsPerBand), 1, hardware);
  parallelFor(size_t(bands), [&](size_t band) {
    rowBand(rows * int(band) / bands, rows * (int(band) + 1) / bands);
  });
}

}  // namespace bounce
