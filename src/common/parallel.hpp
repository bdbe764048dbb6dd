// Threads with results that do not depend on their number (docs/performance.md).
//
// Work is cut into chunks whose size depends on the problem only, never on the
// number of threads; the threads share out whole chunks, and every sum is formed
// per chunk and the chunk sums are added in chunk order. So a run gives the same
// bits on 1, 2 or N threads. Without OpenMP the pragmas are ignored and
// max_threads() is 1.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace exdyn {

// Threads a parallel region uses.
inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Sets the threads of later parallel regions; 0 means every core. Returns the number set.
inline int set_threads(int requested) {
#ifdef _OPENMP
  const int threads = requested > 0 ? requested : omp_get_num_procs();
  omp_set_num_threads(threads);
  return threads;
#else
  (void)requested;
  return 1;
#endif
}

// Nodes per chunk of the nodal loops: large enough to amortise the scheduling,
// small enough to balance two threads on the smallest decks.
inline constexpr std::size_t node_chunk = 2048;

inline std::size_t chunk_count(std::size_t n, std::size_t chunk = node_chunk) {
  return (n + chunk - 1) / chunk;
}

// Calls body(k) for k in [0, count) on the threads, thread t taking the t-th run of
// them (a static schedule: the same nodes and elements on the same core every step).
// Where one thread would run them all (one item, or one thread), a plain loop: a
// parallel region costs libgomp 2-3 us even on one thread (a team set up and a futex
// call), 20 us a step of the Taylor rod's eight regions, 9 % of its step on one
// thread. scripts/serial_fraction.py counts the work inside as the threads' (by the
// name of one_thread_loop on the stack: kept out of line for it); a single item, which
// no number of threads would share, runs in place and counts as serial.
template <class Body>
[[gnu::noinline]] void one_thread_loop(std::ptrdiff_t count, Body& body) {
  for (std::ptrdiff_t k = 0; k < count; ++k) body(k);
}

template <class Body>
void parallel_for_static(std::ptrdiff_t count, Body&& body) {
  if (count <= 1) {  // work that no number of threads would share: serial
    if (count == 1) body(std::ptrdiff_t{0});
    return;
  }
  if (max_threads() == 1) {
    one_thread_loop(count, body);
    return;
  }
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < count; ++k) body(k);
}

// Calls body(begin, end, k) for the chunks k of [0, n) on the threads. body must
// write only to what chunk k owns (e.g. the nodes begin..end-1, partial[k]).
template <class Body>
void for_each_chunk(std::size_t n, Body&& body, std::size_t chunk = node_chunk) {
  parallel_for_static(static_cast<std::ptrdiff_t>(chunk_count(n, chunk)), [&](std::ptrdiff_t k) {
    const std::size_t begin = static_cast<std::size_t>(k) * chunk;
    body(begin, std::min(n, begin + chunk), static_cast<std::size_t>(k));
  });
}

// The sum of partial[0..] in order.
// Neumaier's compensated sum: after the terms are added one by one, sum + error is their
// sum to a few units in the last place of it, however much they cancel.
inline void add_compensated(double& sum, double& error, double term) {
  const double t = sum + term;
  error += (sum < 0 ? -sum : sum) >= (term < 0 ? -term : term) ? (sum - t) + term : (term - t) + sum;
  sum = t;
}

inline double ordered_sum(const std::vector<double>& partial) {
  double sum = 0.0;
  for (const double p : partial) sum += p;
  return sum;
}

}  // namespace exdyn
