// Cost of the bucket global search against the number of slave nodes: a
// distorted n x n master surface and (n+1)^2 slave points just above it (the
// matching-mesh situation of the plate impact, scaled up). Linear cost shows as
// a constant time per slave node.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "contact/bucket_search.hpp"

namespace {

void BM_BucketSearch(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const double h = 1.0;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> jitter(-0.1 * h, 0.1 * h);
  exdyn::NodalVectors master, slaves;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      master.x.push_back(i * h + jitter(rng));
      master.y.push_back(j * h + jitter(rng));
      master.z.push_back(0.2 * h * std::sin(0.1 * i) + jitter(rng));
      slaves.x.push_back(i * h + jitter(rng));
      slaves.y.push_back(j * h + jitter(rng));
      slaves.z.push_back(master.z.back() + 0.01 * h);
    }
  std::vector<std::array<std::uint32_t, 4>> quads;
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  std::vector<exdyn::contact::Box> boxes;
  exdyn::contact::BucketWorkspace workspace;
  std::vector<exdyn::contact::CandidatePair> pairs;
  for (auto _ : state) {
    exdyn::contact::segment_boxes(
        [&](std::uint32_t node) {
          return std::array<double, 3>{master.x[node], master.y[node], master.z[node]};
        },
        quads, 0.5 * h, boxes);
    exdyn::contact::bucket_search(slaves, boxes, 0.0, workspace, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["slave_nodes"] = static_cast<double>(slaves.size());
  state.counters["pairs_per_node"] = static_cast<double>(pairs.size()) / static_cast<double>(slaves.size());
  state.counters["ns_per_slave_node"] =
      benchmark::Counter(static_cast<double>(slaves.size()) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

// 31^2 = 961 ... 1000^2 = 1.0e6 slave nodes
BENCHMARK(BM_BucketSearch)->Arg(30)->Arg(99)->Arg(315)->Arg(999)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
