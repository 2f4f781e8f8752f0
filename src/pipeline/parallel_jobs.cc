// SPDX-License-Identifier: MIT
#include "mirage/pipeline/parallel_jobs.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace mirage::pipeline {

void RunJobs(int total, int threads, const std::function<void(int)>& job,
             const std::function<void(int, int)>& progress) {
  std::atomic<int> next{0};
  std::atomic<int> finished{0};
  // An exception in a worker (out of memory) must reach the caller, not std::terminate.
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto worker = [&]() {
    for (int i = next++; i < total; i = next++) {
      try {
        job(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = total;  // stop handing out jobs
        return;
      }
      const int done = ++finished;
      if (progress) progress(done, total);
    }
  };
  int count = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  count = std::clamp(count, 1, std::max(1, total));
  if (count == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int i = 0; i < count; ++i) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace mirage::pipeline
