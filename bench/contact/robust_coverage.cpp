// How often `robust` misses the closest point, beyond the test suite's cases: the
// cases of tests/contact/test_random_cases.cpp (RobustFindsTheClosestPoint...) on
// other seeds, against the brute-force truth. A study, not a test (the grid is a
// heuristic: near-ties between two minima behind a thin ridge can be missed).
//   contact_robust_coverage [FIRST_SEED [SEEDS [CASES_PER_KIND]]]   (1001 3 5000)
// Prints each miss and the total; exit 0.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "contact/local_search.hpp"
#include "random_cases.hpp"

int main(int argc, char** argv) {
  using namespace exdyn::contact;
  using testing::Distortion;
  const int first_seed = argc > 1 ? std::atoi(argv[1]) : 1001;
  const int seeds = argc > 2 ? std::atoi(argv[2]) : 3;
  const int per_kind = argc > 3 ? std::atoi(argv[3]) : 5000;
  ProjectionSettings settings;
  settings.method = SearchMethod::robust;
  long cases = 0, misses = 0;
  for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
    testing::Random rng(static_cast<std::uint64_t>(seed));
    for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
      for (const Distortion d : {Distortion::mild, Distortion::moderate, Distortion::strong}) {
        for (int k = 0; k < per_kind; ++k) {
          const Segment s = testing::random_segment(rng, type, d);
          const Vec3 point = testing::random_point(rng, s, 1.5, 1.0);
          const testing::Truth truth = testing::brute_force_closest_point(s, point);
          const ProjectionResult r = project(s, point, initial_guess_lsp(s, point), settings);
          ++cases;
          const bool found = r.converged && std::fabs(r.xi[0]) <= 1.0 && std::fabs(r.xi[1]) <= 1.0 &&
                             r.distance <= truth.distance + 1e-10;
          if (found) continue;
          ++misses;
          std::printf("miss: seed %d, %s %s, distance %.6f at (%.4f, %.4f), closest %.6f at (%.4f, %.4f)\n",
                      seed, std::string(name(type)).c_str(), testing::distortion_name(d), r.distance, r.xi[0],
                      r.xi[1], truth.distance, truth.xi[0], truth.xi[1]);
        }
      }
    }
  }
  std::printf("robust: %ld cases, %ld misses\n", cases, misses);
  return 0;
}
