// Random distorted segments and slave points, and the brute-force truth of
// the closest point of a segment: shared by the local search tests and the
// benchmark. Deterministic (own uniform generator over std::mt19937_64).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "contact/local_search.hpp"
#include "contact/segment.hpp"

namespace exdyn::contact::testing {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo, double hi) {
    const double unit = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * unit;
  }

 private:
  std::mt19937_64 engine_;
};

// Node perturbation, each coordinate +- this, on the square [-1,1]^2 x {0}.
enum class Distortion { mild, moderate, strong };
inline double amplitude(Distortion d) {
  switch (d) {
    case Distortion::mild:
      return 0.1;
    case Distortion::moderate:
      return 0.25;
    case Distortion::strong:
      return 0.4;
  }
  return 0.0;
}
inline const char* distortion_name(Distortion d) {
  return d == Distortion::mild ? "mild" : d == Distortion::moderate ? "moderate" : "strong";
}

// A rotation (from a random unit quaternion) and a translation.
struct RigidMotion {
  std::array<std::array<double, 3>, 3> R{};
  Vec3 t{};
  Vec3 apply(const Vec3& p) const {
    return {R[0][0] * p.x + R[0][1] * p.y + R[0][2] * p.z + t.x,
            R[1][0] * p.x + R[1][1] * p.y + R[1][2] * p.z + t.y,
            R[2][0] * p.x + R[2][1] * p.y + R[2][2] * p.z + t.z};
  }
};
inline RigidMotion random_motion(Random& rng, double translation) {
  double q[4];
  double n = 0.0;
  do {
    n = 0.0;
    for (double& c : q) c = rng.uniform(-1.0, 1.0), n += c * c;
  } while (n > 1.0 || n < 1e-3);
  n = std::sqrt(n);
  for (double& c : q) c /= n;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  RigidMotion m;
  m.R = {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
  m.t = {rng.uniform(-translation, translation), rng.uniform(-translation, translation),
         rng.uniform(-translation, translation)};
  return m;
}

inline Segment transformed(const Segment& s, const RigidMotion& m) {
  Segment out = s;
  for (int i = 0; i < node_count(s.type); ++i) out.nodes[i] = m.apply(s.nodes[i]);
  return out;
}

// The flat square, nodes perturbed; quad8 mid-sides perturbed from the mid-points.
inline Segment random_segment(Random& rng, SegmentType type, Distortion distortion) {
  Segment s;
  s.type = type;
  const double a = amplitude(distortion);
  for (int i = 0; i < node_count(type); ++i) {
    s.nodes[i] = {node_xi[i][0] + rng.uniform(-a, a), node_xi[i][1] + rng.uniform(-a, a), rng.uniform(-a, a)};
  }
  return s;
}

// A slave point y(xi_p) + h n(xi_p): above (h > 0), below (h < 0), beside (xi_p outside).
inline Vec3 random_point(Random& rng, const Segment& s, double xi_range, double height) {
  const Xi xi{rng.uniform(-xi_range, xi_range), rng.uniform(-xi_range, xi_range)};
  const SurfacePoint p = evaluate(s, xi);
  return p.y + rng.uniform(-height, height) * outward_normal(p);
}

inline double distance2(const Segment& s, const Vec3& point, Xi xi) {
  const Vec3 r = point - position(s, xi);
  return dot(r, r);
}

// The closest point of the segment, by brute force: f on a dense grid, then
//  - interior: plain Newton from each of the grid's best discrete local minima,
//    kept when it converges inside the square to a point with H positive definite;
//  - edges: golden-section search around the best point of a dense 1D grid;
//  - corners.
struct Truth {
  Xi xi{};
  double distance = 0.0;
  double second_distance = 0.0;  // best distinct local minimum other than the answer (inf if none)
};

template <int Terms>
Truth brute_force_closest_point(const Surface<Terms>& s, const Vec3& point, int n) {
  const auto d2 = [&](Xi xi) {
    const Vec3 r = point - position(s, xi);
    return dot(r, r);
  };
  struct Candidate {
    double f;
    Xi xi;
  };
  std::vector<Candidate> candidates;
  std::vector<double> f(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  const auto coord = [n](int i) { return -1.0 + 2.0 * i / (n - 1); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) f[static_cast<std::size_t>(j * n + i)] = d2({coord(i), coord(j)});
  // Interior: discrete local minima, refined by Newton.
  std::vector<Candidate> seeds;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double v = f[static_cast<std::size_t>(j * n + i)];
      bool minimum = true;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if ((di || dj) && j + dj >= 0 && j + dj < n && i + di >= 0 && i + di < n &&
              f[static_cast<std::size_t>((j + dj) * n + i + di)] < v)
            minimum = false;
      if (minimum) seeds.push_back({v, {coord(i), coord(j)}});
    }
  }
  std::sort(seeds.begin(), seeds.end(), [](const Candidate& a, const Candidate& b) { return a.f < b.f; });
  if (seeds.size() > 8) seeds.resize(8);
  for (const Candidate& seed : seeds) {
    Xi xi = seed.xi;
    bool ok = false;
    for (int k = 0; k < 60; ++k) {
      const SurfacePoint p = evaluate(s, xi);
      const Vec3 r = point - p.y;
      const double g0 = -2 * dot(r, p.a1), g1 = -2 * dot(r, p.a2);
      const double h00 = 2 * (dot(p.a1, p.a1) - dot(r, p.y11)), h01 = 2 * (dot(p.a1, p.a2) - dot(r, p.y12)),
                   h11 = 2 * (dot(p.a2, p.a2) - dot(r, p.y22));
      const double d = h00 * h11 - h01 * h01;
      if (!(h00 > 0 && d > 0)) break;
      const Xi step{-(h11 * g0 - h01 * g1) / d, -(-h01 * g0 + h00 * g1) / d};
      xi = {xi[0] + step[0], xi[1] + step[1]};
      if (std::hypot(step[0], step[1]) < 1e-14) {
        ok = true;
        break;
      }
    }
    if (ok && std::fabs(xi[0]) <= 1.0 && std::fabs(xi[1]) <= 1.0) candidates.push_back({d2(xi), xi});
  }
  // Edges: xi1 = +-1 or xi2 = +-1.
  const int m = 4 * n;
  for (int edge = 0; edge < 4; ++edge) {
    const auto at = [edge](double t) -> Xi {
      switch (edge) {
        case 0:
          return {t, -1.0};
        case 1:
          return {1.0, t};
        case 2:
          return {t, 1.0};
        default:
          return {-1.0, t};
      }
    };
    // All 1D local minima of a dense grid, each refined by golden section.
    std::vector<double> values(static_cast<std::size_t>(m));
    for (int k = 0; k < m; ++k) values[static_cast<std::size_t>(k)] = d2(at(-1.0 + 2.0 * k / (m - 1)));
    for (int k = 0; k < m; ++k) {
      const double v = values[static_cast<std::size_t>(k)];
      if ((k > 0 && values[static_cast<std::size_t>(k - 1)] < v) ||
          (k < m - 1 && values[static_cast<std::size_t>(k + 1)] < v))
        continue;
      const double h = 2.0 / (m - 1);
      double lo = std::max(-1.0, -1.0 + 2.0 * k / (m - 1) - h),
             hi = std::min(1.0, -1.0 + 2.0 * k / (m - 1) + h);
      const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
      double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
      double f1 = d2(at(x1)), f2 = d2(at(x2));
      for (int it = 0; it < 100 && hi - lo > 1e-15; ++it) {
        if (f1 < f2) {
          hi = x2, x2 = x1, f2 = f1, x1 = hi - ratio * (hi - lo), f1 = d2(at(x1));
        } else {
          lo = x1, x1 = x2, f1 = f2, x2 = lo + ratio * (hi - lo), f2 = d2(at(x2));
        }
      }
      const double t = 0.5 * (lo + hi);
      candidates.push_back({d2(at(t)), at(t)});
      for (const double end : {-1.0, 1.0}) candidates.push_back({d2(at(end)), at(end)});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.f < b.f; });
  Truth truth;
  truth.xi = candidates.front().xi;
  truth.distance = std::sqrt(candidates.front().f);
  truth.second_distance = std::numeric_limits<double>::infinity();
  for (const Candidate& c : candidates) {
    if (std::hypot(c.xi[0] - truth.xi[0], c.xi[1] - truth.xi[1]) > 1e-3) {
      truth.second_distance = std::sqrt(c.f);
      break;
    }
  }
  return truth;
}

inline Truth brute_force_closest_point(const Segment& s, const Vec3& point, int n = 81) {
  return s.type == SegmentType::quad4 ? brute_force_closest_point(make_surface<4>(s), point, n)
                                      : brute_force_closest_point(make_surface<8>(s), point, n);
}

}  // namespace exdyn::contact::testing
