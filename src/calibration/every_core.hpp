// Independent tasks on every core: leave-one-out's folds, the scan's points, the local solves from a fit's starts.
// Each task is deterministic and writes only its own slot, so the answers are the same as one after another, only
// sooner. Internal header of src/calibration.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace pneumatic_finger {

/// Runs task(i) for i in [0, count) on every core; the first exception (by i) is rethrown once all have stopped. A
/// call from within a task runs its own tasks one after another on that thread: the folds already fill the cores.
inline void onEveryCore(std::size_t count, const std::function<void(std::size_t)>& task) {
  static thread_local bool inside = false;
  const std::size_t cores = inside ? 1 : std::thread::hardware_concurrency();
  const std::size_t threads = std::max<std::size_t>(1, std::min<std::size_t>(cores, count));
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> failed(count);
  auto work = [&] {
    const bool was = inside;
    inside = true;
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        task(i);
      } catch (...) {
        failed[i] = std::current_exception();
      }
    }
    inside = was;
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace pneumatic_finger
