#pragma once

// The engine's parallel loops: every particle and grid pass goes through these wrappers of oneTBB.
// Under ThreadSanitizer they also tell the race detector about the fork-join edges of each loop:
// oneTBB's scheduler lives in an uninstrumented shared library, so without these edges every pass
// would appear to race with the one before it. The edges are exact: the caller's work happens
// before every task of the loop, every task happens before the caller continues, and tasks of one
// loop stay unordered, so a real race between two tasks of a pass is still reported.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#if defined(__SANITIZE_THREAD__)
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#endif

namespace mpile {

/// Happens-before edges of one fork-join loop for ThreadSanitizer; no code otherwise.
class ForkJoinEdges {
public:
#if defined(__SANITIZE_THREAD__)
  ForkJoinEdges() {
    __tsan_release(&fork_);
  }
  ~ForkJoinEdges() {
    __tsan_acquire(&join_);
  }
  void task_begins() {
    __tsan_acquire(&fork_);
  }
  void task_ends() {
    __tsan_release(&join_);
  }
  /// A reduction's join reads results of finished tasks.
  void join_begins() {
    __tsan_acquire(&join_);
  }
#else
  ForkJoinEdges() = default;
  void task_begins() {}
  void task_ends() {}
  void join_begins() {}
#endif
  ForkJoinEdges(const ForkJoinEdges&) = delete;
  ForkJoinEdges& operator=(const ForkJoinEdges&) = delete;

private:
  [[maybe_unused]] char fork_ = 0;
  [[maybe_unused]] char join_ = 0;
};

/// body(begin, end) over chunks of [0, n), in parallel.
template <class Body> void parallel_for_chunks(std::size_t n, Body&& body) {
  ForkJoinEdges edges;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      edges.task_begins();
                      body(range.begin(), range.end());
                      edges.task_ends();
                    });
}

/// body(i) for every i in [0, n), in parallel.
template <class Body> void parallel_for(std::size_t n, Body&& body) {
  parallel_for_chunks(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i) {
      body(i);
    }
  });
}

/// The lower of two indices found by parts of a reduction, -1 standing for none found: the join of
/// a "first offender" search, whatever the order of the joins.
inline std::int64_t lowest_found(std::int64_t a, std::int64_t b) {
  return a < 0 ? b : (b < 0 ? a : std::min(a, b));
}

/// Reduction of body(begin, end, partial) over chunks of [0, n), joined with combine(a, b). With
/// deterministic = true the split of the range depends only on n and grain, so floating-point sums
/// come out the same for any thread count.
template <class T, class Body, class Combine>
T parallel_reduce(std::size_t n, T identity, Body&& body, Combine&& combine,
                  bool deterministic = false, std::size_t grain = 4096) {
  ForkJoinEdges edges;
  auto chunk = [&](const tbb::blocked_range<std::size_t>& range, T partial) {
    edges.task_begins();
    partial = body(range.begin(), range.end(), partial);
    edges.task_ends();
    return partial;
  };
  auto join = [&](T a, T b) {
    edges.join_begins();
    T joined = combine(a, b);
    edges.task_ends();
    return joined;
  };
  if (deterministic) {
    return tbb::parallel_deterministic_reduce(tbb::blocked_range<std::size_t>(0, n, grain),
                                              identity, chunk, join);
  }
  return tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, n), identity, chunk, join);
}

} // namespace mpile
