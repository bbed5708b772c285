// A small fixed-size thread pool for the CPU BVH builders. The thread that owns the pool is one
// of its workers: wait() and parallelFor() run queued work on the calling thread instead of
// blocking, so a task may itself submit tasks or call parallelFor without deadlocking, and a
// pool of one thread runs everything inline.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace bounce::rt {

class TaskPool {
 public:
  // threadCount counts the calling thread: TaskPool(2) starts one extra thread.
  explicit TaskPool(uint32_t threadCount);
  ~TaskPool();
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  uint32_t threadCount() const { return uint32_t(workers_.size()) + 1; }

  // Queues a task; tasks run in submission order (FIFO), on any thread.
  void submit(std::function<void()> task);
  // Runs queued tasks on this thread until every submitted task (including tasks submitted by
  // tasks) has finished. Rethrows the first exception a task threw.
  void wait();
  // Calls body(i) for every i in [0, count), spread over this thread and any idle worker.
  // Returns when all calls have finished. Safe to call from inside a task.
  void parallelFor(uint32_t count, const std::function<void(uint32_t)>& body);

 private:
  void workerLoop();
  bool runOneTask(std::unique_lock<std::mutex>& lock);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  uint64_t unfinished_ = 0;  // submitted tasks not yet finished (guarded by mutex_)
  bool stopping_ = false;
  std::exception_ptr firstError_;
};

}  // namespace bounce::rt
