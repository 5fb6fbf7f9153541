// punch/src/parallel.hpp: independent tasks on a few threads (the finite-difference columns of a
// coupled solve's Jacobian; solve_options::threads).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace rhabel::punch::detail {

/// The number of threads that solve_options::threads asks for: 0 means every core the machine
/// reports (at least 1).
inline std::size_t worker_count(std::size_t requested) {
  if (requested > 0) return requested;
  return std::max<std::size_t>(1, std::thread::hardware_concurrency());
}

/// task(0) ... task(count - 1), each exactly once, on min(threads, count) threads (the calling
/// thread is one of them). task must not throw (capture failures in its own result) and must touch
/// only its own output: the tasks' order of execution is not fixed, so results do not depend on
/// the thread count only if each task's result is a function of its index alone.
template <class Task>
void run_tasks(std::size_t count, std::size_t threads, Task&& task) {
  const std::size_t workers = std::min(worker_count(threads), count);
  if (workers <= 1) {
    for (std::size_t k = 0; k < count; ++k) task(k);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k = next++; k < count; k = next++) task(k);
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

}  // namespace rhabel::punch::detail
