// Throughput of the element loop, add_internal_forces: element-cycles per second
// (elements x calls / wall second) on one core, for
//   hex8 on a structured box (parallelepiped kernel),
//   hex8 on the same box with every interior node moved randomly by up to h/10
//   (general 2x2x2 kernel), and hex8r on both meshes;
//   hex20 and hex20r on a box part of the mesher (the shared element matrix) and
//   on the same part distorted (perturbation 0.1: the Gauss point kernel).
// Boxes of n^3 elements, n = 22, 46, 100 (1.06e4, 9.7e4, 1e6 elements); 20-node
// boxes of m^3 elements, m = n / 2 (the same node spacing: about the same nodes). The
// displacement is a smooth non-trivial field plus noise, so every mode is loaded.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <tuple>
#include <vector>

#include "common/parallel.hpp"
#include "element/element_block.hpp"
#include "material/elastic.hpp"
#include "mesh/mesh.hpp"

namespace {

using exdyn::NodalVectors;
using exdyn::input::Formulation;
namespace element = exdyn::element;

struct Model {
  NodalVectors x_ref, u, f_int;
  std::vector<std::uint32_t> connectivity;
  std::vector<double> stress;
  element::ElementBlock block;
};

// A smooth non-trivial displacement plus noise (every mode loaded), zero forces
// and stresses for `count` elements; `length` the box side, m.
void load(Model& model, double length, std::uint32_t count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::size_t node_count = model.x_ref.size();
  model.u.resize(node_count);
  model.f_int.resize(node_count);
  for (std::size_t id = 0; id < node_count; ++id) {
    const double x = model.x_ref.x[id] / length, y = model.x_ref.y[id] / length,
                 z = model.x_ref.z[id] / length;
    model.u.x[id] = 1e-6 * (std::sin(3 * x + y) + 0.1 * unit(rng));
    model.u.y[id] = 1e-6 * (std::cos(2 * y - z) * x + 0.1 * unit(rng));
    model.u.z[id] = 1e-6 * (x * y * z + 0.1 * unit(rng));
  }
  model.stress.assign(6 * static_cast<std::size_t>(count), 0.0);
}

// A box of n^3 cubes of side h, nodes numbered x fastest (like a structured mesh generator).
std::unique_ptr<Model> make_model(int n, Formulation formulation, bool distorted) {
  auto model = std::make_unique<Model>();
  const double h = 1.0e-3;
  const int np = n + 1;
  const auto node = [np](int i, int j, int k) { return static_cast<std::uint32_t>(i + np * (j + np * k)); };
  const std::size_t node_count = static_cast<std::size_t>(np) * np * np;
  model->x_ref.resize(node_count);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < np; ++k)
    for (int j = 0; j < np; ++j)
      for (int i = 0; i < np; ++i) {
        const std::uint32_t id = node(i, j, k);
        const bool interior = i > 0 && j > 0 && k > 0 && i < n && j < n && k < n;
        const double jitter = distorted && interior ? 0.1 * h : 0.0;
        model->x_ref.x[id] = i * h + jitter * unit(rng);
        model->x_ref.y[id] = j * h + jitter * unit(rng);
        model->x_ref.z[id] = k * h + jitter * unit(rng);
      }
  model->connectivity.reserve(8 * static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::uint32_t nodes[8] = {
            node(i, j, k),     node(i + 1, j, k),     node(i + 1, j + 1, k),     node(i, j + 1, k),
            node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        model->connectivity.insert(model->connectivity.end(), nodes, nodes + 8);
      }
  const std::uint32_t count = static_cast<std::uint32_t>(n) * n * n;
  const auto steel = exdyn::material::elastic_constants(2.1e11, 0.3, 7800.0);
  model->block = element::make_element_block(formulation, steel, 0.05, 0, count, model->connectivity.data(),
                                             model->x_ref);
  load(*model, n * h, count, rng);
  return model;
}

// A 20-node box part of m^3 cubes of side 2h, from the mesher.
std::unique_ptr<Model> make_quadratic_model(int m, Formulation formulation, bool distorted) {
  auto model = std::make_unique<Model>();
  const double h = 1.0e-3;
  exdyn::input::Deck deck;
  exdyn::input::PartOptions part;
  part.name = "box";
  part.box_max = {2 * h * m, 2 * h * m, 2 * h * m};
  part.elements = {m, m, m};
  part.formulation = formulation;
  part.perturbation_fraction = distorted ? 0.1 : 0.0;
  deck.parts = {part};
  exdyn::mesh::Mesh mesh = exdyn::mesh::build_mesh(deck);
  model->x_ref = std::move(mesh.x_ref);
  model->connectivity = std::move(mesh.connectivity);
  const std::uint32_t count = static_cast<std::uint32_t>(m) * m * m;
  const auto steel = exdyn::material::elastic_constants(2.1e11, 0.3, 7800.0);
  model->block = element::make_element_block(formulation, steel, exdyn::input::HourglassControl{}, 0, count,
                                             model->connectivity.data(), model->x_ref);
  std::mt19937_64 rng(7);
  load(*model, 2 * h * m, count, rng);
  return model;
}

Model& cached_model(int n, Formulation formulation, bool distorted) {
  static std::map<std::tuple<int, int, bool>, std::unique_ptr<Model>> cache;
  const auto key = std::make_tuple(n, static_cast<int>(formulation), distorted);
  auto it = cache.find(key);
  if (it == cache.end()) {
    cache.clear();  // keep one model in memory at a time (1e6 general hex8 data is ~650 MB)
    it = cache
             .emplace(key, exdyn::input::is_quadratic(formulation)
                               ? make_quadratic_model(n / 2, formulation, distorted)
                               : make_model(n, formulation, distorted))
             .first;
  }
  return *it->second;
}

void run(benchmark::State& state, Formulation formulation, bool distorted) {
  Model& model = cached_model(static_cast<int>(state.range(0)), formulation, distorted);
  const int threads = exdyn::set_threads(static_cast<int>(state.range(1)));
  double energy = 0.0;
  for (auto _ : state) {
    const element::ElementEnergies e =
        element::add_internal_forces(model.block, model.u, model.f_int, model.stress.data());
    energy += e.strain + e.hourglass;
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(energy);
  state.counters["elements"] = static_cast<double>(model.block.count);
  state.counters["threads"] = threads;
  state.counters["element_cycles_per_second"] = benchmark::Counter(
      static_cast<double>(model.block.count), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["parallelepiped_kernel"] = element::uses_parallelepiped_kernel(model.block) ? 1.0 : 0.0;
  state.counters["reference_bytes_per_element"] =
      static_cast<double>(model.block.reference.size() * sizeof(double)) / model.block.count;
}

void hex8_box(benchmark::State& state) { run(state, Formulation::hex8, false); }
void hex8_distorted(benchmark::State& state) { run(state, Formulation::hex8, true); }
void hex8r_box(benchmark::State& state) { run(state, Formulation::hex8r, false); }
void hex8r_distorted(benchmark::State& state) { run(state, Formulation::hex8r, true); }
void hex20_box(benchmark::State& state) { run(state, Formulation::hex20, false); }
void hex20_distorted(benchmark::State& state) { run(state, Formulation::hex20, true); }
void hex20r_box(benchmark::State& state) { run(state, Formulation::hex20r, false); }
void hex20r_distorted(benchmark::State& state) { run(state, Formulation::hex20r, true); }

// Arguments: n (boxes of n^3 elements: 1.06e4, 9.7e4, 1e6) and the threads (1, 2).
// Rates are per wall-clock second (UseRealTime), the only fair measure once the
// loop runs on several threads; on a shared machine they include waiting for a core.
#define EXDYN_ELEMENT_BENCHMARK(name)        \
  BENCHMARK(name)                            \
      ->ArgsProduct({{22, 46, 100}, {1, 2}}) \
      ->ArgNames({"n", "threads"})           \
      ->UseRealTime()                        \
      ->Unit(benchmark::kMillisecond)
EXDYN_ELEMENT_BENCHMARK(hex8_box);
EXDYN_ELEMENT_BENCHMARK(hex8_distorted);
EXDYN_ELEMENT_BENCHMARK(hex8r_box);
EXDYN_ELEMENT_BENCHMARK(hex8r_distorted);
EXDYN_ELEMENT_BENCHMARK(hex20_box);
EXDYN_ELEMENT_BENCHMARK(hex20_distorted);
EXDYN_ELEMENT_BENCHMARK(hex20r_box);
EXDYN_ELEMENT_BENCHMARK(hex20r_distorted);

}  // namespace

BENCHMARK_MAIN();
