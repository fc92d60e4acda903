#pragma once

// Bitwise comparison of run results, for the thread-count identity tests.

#include "engine/particles.hpp"
#include "engine/structures/rigid_body.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <vector>

namespace mpile {

/// Runs `work` on exactly `threads` worker threads (more than the machine's cores are allowed, so
/// that three threads really run on a two-core machine).
template <class Work> void with_threads(int threads, Work&& work) {
  const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
  tbb::task_arena arena(threads);
  arena.execute(work);
}

/// The thread counts a thread test compares with one thread: two and three (an odd count of
/// workers on two cores), two alone under ThreadSanitizer, whose race detection needs two threads
/// sharing the passes, not a third, and whose runs cost 10 to 40 times their release time.
inline std::vector<int> threads_compared_with_one() {
#if defined(__SANITIZE_THREAD__)
  return {2};
#else
  return {2, 3};
#endif
}

/// One thread, then threads_compared_with_one().
inline std::vector<int> compared_thread_counts() {
  std::vector<int> counts{1};
  for (const int threads : threads_compared_with_one()) {
    counts.push_back(threads);
  }
  return counts;
}

template <class T> bool bitwise_equal(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Positions, velocities, volumes, stresses and particle order, bit for bit.
inline void expect_particles_identical(const Particles& a, const Particles& b) {
  EXPECT_TRUE(bitwise_equal(a.r, b.r));
  EXPECT_TRUE(bitwise_equal(a.y, b.y));
  EXPECT_TRUE(bitwise_equal(a.v_r, b.v_r));
  EXPECT_TRUE(bitwise_equal(a.v_y, b.v_y));
  EXPECT_TRUE(bitwise_equal(a.v_theta, b.v_theta));
  EXPECT_TRUE(bitwise_equal(a.u_theta, b.u_theta));
  EXPECT_TRUE(bitwise_equal(a.volume, b.volume));
  EXPECT_TRUE(bitwise_equal(a.stress, b.stress));
  EXPECT_TRUE(bitwise_equal(a.r0, b.r0)); // same particle order
}

/// Each rigid body's velocity and the contact force on it, bit for bit.
inline void expect_rigid_bodies_identical(const std::vector<RigidBody>& a,
                                          const std::vector<RigidBody>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(std::memcmp(&a[k].velocity, &b[k].velocity, sizeof(a[k].velocity)), 0);
    EXPECT_EQ(std::memcmp(&a[k].contact, &b[k].contact, sizeof(a[k].contact)), 0);
  }
}

} // namespace mpile
