#include "rt/task_pool.h"

#include <memory>

namespace bounce::rt {

TaskPool::TaskPool(uint32_t threadCount) {
  for (uint32_t i = 1; i < threadCount; ++i) workers_.emplace_back([this] { workerLoop(); });
}

TaskPool::~TaskPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void TaskPool::submit(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
    ++unfinished_;
  }
  wake_.notify_one();
}

// Pops and runs one task with the lock released; returns false when the queue is empty.
bool TaskPool::runOneTask(std::unique_lock<std::mutex>& lock) {
  if (queue_.empty()) return false;
  std::function<void()> task = std::move(queue_.front());
  queue_.pop_front();
  lock.unlock();
  std::exception_ptr error;
  try {
    task();
  } catch (...) {
    error = std::current_exception();
  }
  lock.lock();
  if (error && !firstError_) firstError_ = error;
  if (--unfinished_ == 0) wake_.notify_all();
  return true;
}

void TaskPool::workerLoop() {
  std::unique_lock lock(mutex_);
  while (true) {
    if (runOneTask(lock)) continue;
    if (stopping_) return;
    wake_.wait(lock);
  }
}

void TaskPool::wait() {
  std::unique_lock lock(mutex_);
  while (unfinished_ > 0) {
    if (!runOneTask(lock)) wake_.wait(lock);
  }
  if (firstError_) {
    std::exception_ptr error = firstError_;
    firstError_ = nullptr;
    std::rethrow_exception(error);
  }
}

void TaskPool::parallelFor(uint32_t count, const std::function<void(uint32_t)>& body) {
  // Indices are claimed through an atomic counter by the caller and by helper tasks; a helper
  // that starts after every index is claimed returns at once, so the shared state outlives the
  // call but `body` is only touched while the caller is still waiting.
  struct Shared {
    std::atomic<uint32_t> next{0};
    std::atomic<uint32_t> finished{0};
    uint32_t count = 0;
    const std::function<void(uint32_t)>* body = nullptr;
    std::mutex errorMutex;
    std::exception_ptr error;
  };
  auto shared = std::make_shared<Shared>();
  shared->count = count;
  shared->body = &body;
  auto work = [shared] {
    for (uint32_t i; (i = shared->next.fetch_add(1)) < shared->count;) {
      try {
        (*shared->body)(i);
      } catch (...) {
        std::lock_guard lock(shared->errorMutex);
        if (!shared->error) shared->error = std::current_exception();
      }
      shared->finished.fetch_add(1, std::memory_order_release);
    }
  };
  uint32_t helpers = std::min<uint32_t>(uint32_t(workers_.size()), count > 0 ? count - 1 : 0);
  for (uint32_t i = 0; i < helpers; ++i) submit(work);
  work();
  // Only indices already being run by helpers remain; they are short, so spin politely.
  while (shared->finished.load(std::memory_order_acquire) < count) std::this_thread::yield();
  if (shared->error) std::rethrow_exception(shared->error);
}

}  // namespace bounce::rt
