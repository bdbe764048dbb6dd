// The setup of the plate impact at mesh M (2 x M x 1 x M hex8 elements), M = 200, 400,
// 1000, on one core: what every rank does before its first step.
//   WholeModel:   build_model, as every rank of a deck set up whole does (and one
//                 process);
//   LatticeWalk:  the walk of every chunk that each rank set up rank by rank repeats
//                 (centroids, colours, the bisection for 8 ranks: setup_chunks);
//   HaloMasses:   the lumped masses of an eighth of the nodes from the elements around
//                 them (setup_masses), a rank's share on 8 ranks.
// Reported as elements per second of the whole model.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "input/deck_reader.hpp"
#include "model/model.hpp"
#include "ranks/rank_setup.hpp"

namespace {

using namespace exdyn;

input::Deck plates(int mesh) {
  input::Deck deck = input::read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/plate_impact.yaml", {});
  for (auto& part : deck.parts) part.elements = {mesh, 1, mesh};
  return deck;
}

void WholeModel(benchmark::State& state) {
  const input::Deck deck = plates(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(solver::build_model(deck));
  state.counters["elements/s"] = benchmark::Counter(2.0 * double(state.range(0) * state.range(0)),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}

void LatticeWalk(benchmark::State& state) {
  const input::Deck deck = plates(int(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(solver::setup_chunks(deck, 8, solver::Partitioning::bisection));
  state.counters["elements/s"] = benchmark::Counter(2.0 * double(state.range(0) * state.range(0)),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}

void HaloMasses(benchmark::State& state) {
  const input::Deck deck = plates(int(state.range(0)));
  const auto m = std::uint32_t(state.range(0));
  std::vector<std::uint32_t> nodes(2 * (m + 1) * 2 * (m + 1) / 8);
  std::iota(nodes.begin(), nodes.end(), 0u);
  for (auto _ : state) benchmark::DoNotOptimize(solver::setup_masses(deck, nodes));
  state.counters["elements/s"] = benchmark::Counter(2.0 * double(state.range(0) * state.range(0)),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(WholeModel)->Arg(200)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(LatticeWalk)->Arg(200)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(HaloMasses)->Arg(200)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
