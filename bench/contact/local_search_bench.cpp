// Nanoseconds per projection, for every method on quad4 and quad8 segments,
// mildly and strongly distorted (tests/contact/random_cases.hpp), from the
// LSP initial guess. Each benchmark cycles through a fixed set of 256 random
// cases (a contact loop's mix); the counters report the mean iterations and
// the share of cases where the method converged to a minimum.
//
// "newton_ok" variants time only the cases where Newton converges to the
// closest point of the segment: `robust` there is the comparison the issue asks
// for (within 2x of newton).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "contact/local_search.hpp"
#include "random_cases.hpp"

namespace {

using namespace exdyn::contact;
using exdyn::contact::testing::Distortion;

struct Case {
  Segment segment;
  Vec3 point;
  Xi start;
};

std::vector<Case> make_cases(SegmentType type, Distortion distortion, bool only_newton_ok) {
  testing::Random rng(2026 + static_cast<int>(type) * 10 + static_cast<int>(distortion));
  std::vector<Case> cases;
  ProjectionSettings newton;
  newton.method = SearchMethod::newton;
  while (cases.size() < 256) {
    const Segment s = testing::random_segment(rng, type, distortion);
    // Slave points over the segment, near it (a contact search's usual case).
    const Vec3 point = testing::random_point(rng, s, 0.9, 0.3);
    const Xi start = initial_guess_lsp(s, point);
    if (only_newton_ok) {
      const ProjectionResult r = project(s, point, start, newton);
      const testing::Truth truth = testing::brute_force_closest_point(s, point, 41);
      if (!(r.converged && r.inside && r.distance <= truth.distance + 1e-10)) continue;
    }
    cases.push_back({s, point, start});
  }
  return cases;
}

void bench_projection(benchmark::State& state, SearchMethod method, SegmentType type, Distortion distortion,
                      bool only_newton_ok) {
  const std::vector<Case> cases = make_cases(type, distortion, only_newton_ok);
  ProjectionSettings settings;
  settings.method = method;
  settings.tolerance = 1e-10;
  settings.max_iterations = 100;
  const ProjectFn project_fn = select_method(method);  // chosen once, outside the loop
  std::size_t k = 0;
  long iterations = 0, minima = 0, count = 0;
  for (auto _ : state) {
    const Case& c = cases[k];
    const ProjectionResult r = project_fn(c.segment, c.point, c.start, settings);
    benchmark::DoNotOptimize(r);
    iterations += r.iterations;
    minima += r.converged && r.stationary == StationaryKind::minimum;
    ++count;
    k = (k + 1) & 255;
  }
  state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(count);
  state.counters["converged_min"] = static_cast<double>(minima) / static_cast<double>(count);
}

void register_all() {
  for (const auto& [method, method_name] : search_method_names) {
    for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
      for (const Distortion d : {Distortion::mild, Distortion::strong}) {
        const std::string label =
            std::string(method_name) + "/" + std::string(name(type)) + "/" + testing::distortion_name(d);
        benchmark::RegisterBenchmark(label.c_str(), bench_projection, method, type, d, false);
      }
    }
  }
  for (const SearchMethod method : {SearchMethod::newton, SearchMethod::robust, SearchMethod::bfgs}) {
    for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
      for (const Distortion d : {Distortion::mild, Distortion::strong}) {
        const std::string label = std::string(name(method)) + "/" + std::string(name(type)) + "/" +
                                  testing::distortion_name(d) + "/newton_ok";
        benchmark::RegisterBenchmark(label.c_str(), bench_projection, method, type, d, true);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
