// `robust`: the closest point of the segment itself, xi in [-1,1]^2
// (docs/local-search.md, "The robust method"):
//  1. seeds from f on a 9 x 9 grid over [-1,1]^2: (a) the grid's discrete local
//     minima, (b) points of the edges that are discrete minima along the edge
//     where f decreases out of the square; the clamped initial guess if better;
//  2. from each seed, Newton with an active set on the bounds (a bound whose
//     gradient points out of the square is held); damped (|eigenvalues|, plus a
//     move along negative curvature) when H is not positive definite; the step
//     cut to one grid spacing, projected onto the square and halved until f
//     decreases (Armijo);
//  3. a Hessian check on the free variables at the end of each descent:
//     negative curvature restarts from a point moved along it;
//  4. second chances: (c) grid points whose f is within lambda h^2 / 4 of the
//     best and far from every point found; (d) along an edge near an interior
//     point found; (e) just inside an edge point found;
//  5. the lowest f over all descents.
// Fast path (0.): when a bound shows f strictly convex on the whole square, its one
// minimum there is the closest point, and one constrained Newton descent from the
// caller's guess finds it: no grid, no second chances.
#include <algorithm>
#include <cmath>

#include "contact/methods/kernel_support.hpp"
#include "contact/methods/robust_proof.hpp"

namespace exdyn::contact {
namespace {

using namespace detail;
using robust_proof::closest_within;
using robust_proof::convex_bound;

constexpr int grid_points = 9;                        // per direction, including the edges
constexpr int max_seeds = 8;                          // Newton runs, at most
constexpr int max_second_chances = 8;                 // further Newton runs, at most
constexpr int max_restarts = 3;                       // Hessian-check restarts per seed
constexpr double max_step = 2.0 / (grid_points - 1);  // parametric
constexpr double armijo = 1.0e-4;                     // sufficient decrease
constexpr double escape_step = 0.25;                  // parametric move off a saddle or maximum

inline double clamp1(double x) { return std::clamp(x, -1.0, 1.0); }
inline Xi clamp_box(Xi x) { return {clamp1(x[0]), clamp1(x[1])}; }

// Active bound: at the bound with the gradient pointing out of the square.
inline bool held(double x, double g) { return (x >= 1.0 && g < 0.0) || (x <= -1.0 && g > 0.0); }

struct Run {
  Xi xi;
  double f;
  bool converged;
};

template <int Terms>
class RobustSearch {
 public:
  RobustSearch(const Surface<Terms>& s, const Vec3& ys, const ProjectionSettings& settings,
               ProjectionResult& counts)
      : s_(s), ys_(ys), settings_(settings), counts_(counts) {
    const double size = std::sqrt(size2(s));
    f_noise_ = 1.0e-14 * (size * size + dot(ys - s.c[0], ys - s.c[0]));
  }

  // Constrained damped Newton from `start` (inside the square), with the
  // Hessian check and its restarts.
  Run descend(Xi start) {
    Xi xi = start;
    Local l = evaluate_local(s_, ys_, xi);
    ++counts_.evaluations;
    bool converged = false;
    for (int restart = 0; restart <= max_restarts; ++restart) {
      converged = newton(xi, l);
      // Hessian check on the free variables.
      const bool free0 = !fixed(xi, l, 0), free1 = !fixed(xi, l, 1);
      const double zero = curvature_zero(l);
      Xi direction{0.0, 0.0};
      if (free0 && free1) {
        const Xi lambda = eigenvalues(l.H);
        if (lambda[0] < -zero) direction = eigenvector(l.H, lambda[0]);
      } else if (free0) {
        if (l.H.xx < -zero) direction = {1.0, 0.0};
      } else if (free1) {
        if (l.H.yy < -zero) direction = {0.0, 1.0};
      }
      if (direction[0] == 0.0 && direction[1] == 0.0) break;
      // Move along +-direction, whichever lowers f; none does: stay.
      const Xi plus = clamp_box(xi + scaled(escape_step, direction));
      const Xi minus = clamp_box(xi - scaled(escape_step, direction));
      const Local lp = evaluate_local(s_, ys_, plus);
      const Local lm = evaluate_local(s_, ys_, minus);
      counts_.evaluations += 2;
      const Local& better = lp.f <= lm.f ? lp : lm;
      if (!(better.f < l.f)) break;
      xi = lp.f <= lm.f ? plus : minus;
      l = better;
    }
    return {xi, l.f, converged};
  }

  // The same with xi[a] held at its bound whatever the gradient: the
  // constrained minimum along that edge. Kept only when it is a minimum of
  // the square's problem there (the gradient points out of the square).
  Run descend_on_edge(Xi start, int a) {
    pinned_ = a;
    Run run = descend(start);
    pinned_ = -1;
    const LocalGradient lg = evaluate_gradient(s_, ys_, run.xi);
    ++counts_.evaluations;
    if (!held(run.xi[a], lg.g[a])) run.f = std::numeric_limits<double>::infinity();
    return run;
  }

  // Steps until |step| <= tolerance; returns whether that test was met.
  bool newton(Xi& xi, Local& l) {
    for (int k = 0; k < settings_.max_iterations; ++k) {
      ++counts_.iterations;
      Xi p = direction(xi, l);
      if (p[0] == 0.0 && p[1] == 0.0) return true;  // a corner held by both bounds, or g = 0
      // At most one grid spacing per step: stay in the seed's basin.
      const double length = norm2(p);
      if (length > max_step) p = scaled(max_step / length, p);
      LineSearch outcome = line_search(xi, l, p);
      if (outcome == LineSearch::full_step_within_tolerance) return true;
      if (outcome == LineSearch::no_decrease) {
        // The projected Newton step may fail to descend when a bound and the
        // off-diagonal of H interact: fall back to the projected gradient.
        const Xi q = gradient_direction(xi, l);
        if (q[0] == 0.0 && q[1] == 0.0) return true;
        outcome = line_search(xi, l, q);
        if (outcome != LineSearch::accepted) return true;  // no descent left: a local minimum
      }
    }
    return false;
  }

 private:
  enum class LineSearch { accepted, full_step_within_tolerance, no_decrease };

  // Projected backtracking along p: halve until f decreases enough (Armijo).
  LineSearch line_search(Xi& xi, Local& l, Xi p) {
    double t = 1.0;
    for (;;) {
      const Xi trial = clamp_box(xi + scaled(t, p));
      const Xi step = trial - xi;
      const double step_norm = norm2(step);
      if (step_norm <= settings_.tolerance) {
        if (t < 1.0) return LineSearch::no_decrease;
        xi = trial;  // the full step is within the tolerance: the stopping test is met
        if (step_norm > 0.0) {
          l = evaluate_local(s_, ys_, xi);
          ++counts_.evaluations;
        }
        return LineSearch::full_step_within_tolerance;
      }
      const Local lt = evaluate_local(s_, ys_, trial);
      ++counts_.evaluations;
      if (lt.f <= l.f + armijo * std::min(dot2(l.g, step), 0.0) + f_noise_) {
        xi = trial;
        l = lt;
        return LineSearch::accepted;
      }
      t *= 0.5;
    }
  }

  // -g on the free variables, with the exact step along it when the curvature
  // is positive, else a parametric length of 2.
  Xi gradient_direction(Xi xi, const Local& l) const {
    Xi p{fixed(xi, l, 0) ? 0.0 : -l.g[0], fixed(xi, l, 1) ? 0.0 : -l.g[1]};
    const double pp = dot2(p, p);
    if (!(pp > 0.0)) return {0.0, 0.0};
    const double curvature = dot2(p, l.H * p);
    const double alpha = curvature > 0.0 ? pp / curvature : 2.0 / std::sqrt(pp);
    return scaled(alpha, p);
  }

  // Variable a does not move: an active bound, or the edge of descend_on_edge.
  bool fixed(Xi xi, const Local& l, int a) const { return a == pinned_ || held(xi[a], l.g[a]); }

  double curvature_zero(const Local& l) const {
    const double r_norm = std::sqrt(l.f);
    return eigenvalue_tolerance * 2.0 *
           (l.A.xx + l.A.yy + r_norm * (norm(l.p.y11) + 2.0 * norm(l.p.y12) + norm(l.p.y22)));
  }

  static Xi eigenvector(const Sym2& H, double lambda) {
    // (H - lambda I) v = 0: take the longer of the two row-derived candidates.
    const Xi v1{H.xy, lambda - H.xx};
    const Xi v2{lambda - H.yy, H.xy};
    const Xi v = dot2(v1, v1) >= dot2(v2, v2) ? v1 : v2;
    const double length = norm2(v);
    return length > 0.0 ? scaled(1.0 / length, v) : Xi{1.0, 0.0};
  }

  // The search direction on the free variables.
  Xi direction(Xi xi, const Local& l) const {
    const bool free0 = !fixed(xi, l, 0), free1 = !fixed(xi, l, 1);
    const double zero = curvature_zero(l);
    if (free0 && free1) {
      const double d = det(l.H);
      if (l.H.xx > zero && d > zero * zero && !is_singular(l.H))
        return scaled(-1.0, inverse(l.H) * l.g);  // Newton
      // Damped Newton: H's eigenvalues replaced by max(|lambda|, zero).
      const Xi lambda = eigenvalues(l.H);
      Xi p{0.0, 0.0};
      for (int i = 0; i < 2; ++i) {
        const Xi v = eigenvector(l.H, lambda[i]);
        const double gv = dot2(v, l.g);
        p = p - scaled(gv / std::max(std::fabs(lambda[i]), zero), v);
      }
      // Also go down along the negative curvature (escapes a saddle where g = 0).
      if (lambda[0] < -zero) {
        const Xi v = eigenvector(l.H, lambda[0]);
        const double sign = dot2(v, l.g) > 0.0 ? -1.0 : 1.0;
        p = p + scaled(sign * escape_step, v);
      }
      return p;
    }
    if (free0 || free1) {
      const int j = free0 ? 0 : 1;
      const double h = j == 0 ? l.H.xx : l.H.yy;
      Xi p{0.0, 0.0};
      if (h > zero) {
        p[j] = -l.g[j] / h;
      } else if (l.g[j] != 0.0) {
        p[j] = l.g[j] > 0.0 ? -2.0 : 2.0;  // no positive curvature: downhill to the far bound, then halve
      }
      return p;
    }
    return {0.0, 0.0};
  }

  const Surface<Terms>& s_;
  Vec3 ys_;
  const ProjectionSettings& settings_;
  ProjectionResult& counts_;
  double f_noise_ = 0.0;
  int pinned_ = -1;  // a variable held at its bound by descend_on_edge, or -1
};

// On an edge or a corner with the gradient pointing out of the square beyond the
// stationarity tolerance: the unconstrained closest point lies outside the segment.
template <int Terms>
bool pushed_out_of_square(const Surface<Terms>& s, Xi xi, const Local& l) {
  const double gradient_floor = stationary_gradient_tolerance * 2.0 * std::sqrt(l.A.xx + l.A.yy) *
                                (std::sqrt(l.f) + std::sqrt(size2(s)));
  for (int a = 0; a < 2; ++a)
    if (held(xi[a], l.g[a]) && std::fabs(l.g[a]) > gradient_floor) return true;
  return false;
}

// Newton's iterations from the guess (as `newton`, at most max_iterations, left when
// xi leaves [-2,2]^2), then the proof above at the point they converge to, when it is
// inside the square. Fills `result` and returns true when the proof holds.
template <int Terms>
bool certified_newton(const Surface<Terms>& s, const Vec3& ys, Xi xi, const ProjectionSettings& settings,
                      ProjectionResult& result, Run& newton_point) {
  Local l = evaluate_local(s, ys, xi);
  ++result.evaluations;
  for (int k = 0; k < settings.max_iterations; ++k) {
    ++result.iterations;
    if (is_singular(l.H)) return false;
    const Xi step = scaled(-1.0, inverse(l.H) * l.g);
    xi = xi + step;
    if (!(std::fabs(xi[0]) <= 2.0 && std::fabs(xi[1]) <= 2.0)) return false;  // NaN included
    l = evaluate_local(s, ys, xi);
    ++result.evaluations;
    if (norm2(step) <= settings.tolerance) {
      if (!(std::fabs(xi[0]) <= 1.0 && std::fabs(xi[1]) <= 1.0)) return false;
      if (!closest_within(s, xi, l, settings.tolerance)) {
        if (eigenvalues(l.H)[0] > 0.0) newton_point = {xi, l.f, true};  // a strict local minimum
        return false;
      }
      result.xi = xi;
      result.converged = true;
      result.failure = FailureReason::none;
      result.on_boundary = false;  // |g| within epsilon growth: stationary, not pushed out
      finish_at(s, l, result);     // l is at xi: no evaluation again
      return true;
    }
  }
  return false;
}

// Projected Newton on f strictly convex on the square (H positive definite there,
// so every Newton step on the free variables is downhill and the one KKT point is the
// closest point). A variable at a bound whose gradient points out of the square is
// held. Each trial is evaluated once and, when f decreases (with the rounding
// allowance), becomes the next iterate: as cheap per iteration as `newton`. Fills
// `result` (xi, converged, on_boundary, counts) and returns true on convergence, a
// full Newton step <= tolerance; returns false when a step must be cut to that length
// (a projected step that does not descend) or max_iterations run out.
template <int Terms>
bool convex_newton(const Surface<Terms>& s, const Vec3& ys, Xi xi, const ProjectionSettings& settings,
                   ProjectionResult& result) {
  const double f_noise = 1.0e-14 * (size2(s) + dot(ys - s.c[0], ys - s.c[0]));
  Local l = evaluate_local(s, ys, xi);
  ++result.evaluations;
  for (int k = 0; k < settings.max_iterations; ++k) {
    ++result.iterations;
    const bool free0 = !held(xi[0], l.g[0]), free1 = !held(xi[1], l.g[1]);
    Xi p{0.0, 0.0};
    if (free0 && free1) {
      p = scaled(-1.0, inverse(l.H) * l.g);
    } else if (free0) {
      p[0] = -l.g[0] / l.H.xx;
    } else if (free1) {
      p[1] = -l.g[1] / l.H.yy;
    }
    for (double t = 1.0;; t *= 0.5) {
      const Xi trial = clamp_box(xi + scaled(t, p));
      if (!finite(trial)) return false;
      if (norm2(trial - xi) <= settings.tolerance) {
        if (t < 1.0) return false;
        result.xi = trial;
        result.converged = true;
        result.failure = FailureReason::none;
        // g of the last iterate, within the tolerance of trial.
        result.on_boundary = pushed_out_of_square(s, trial, l);
        return true;
      }
      const Local lt = evaluate_local(s, ys, trial);
      ++result.evaluations;
      if (lt.f <= l.f + f_noise) {
        xi = trial;
        l = lt;
        break;
      }
    }
  }
  return false;
}

// f on the grid, row by row: y(u, v) = A(v) + u B(v) + u^2 C(v).
template <int Terms>
void grid_values(const Surface<Terms>& s, const Vec3& ys, std::array<double, grid_points * grid_points>& f) {
  const auto& c = s.c;
  for (int j = 0; j < grid_points; ++j) {
    const double v = -1.0 + 2.0 * j / (grid_points - 1);
    Vec3 A = ys - (c[0] + v * c[2]);
    Vec3 B = c[1] + v * c[3];
    Vec3 C{};
    if constexpr (Terms == 8) {
      A = A - (v * v) * c[5];
      B = B + (v * v) * c[7];
      C = c[4] + v * c[6];
    }
    for (int i = 0; i < grid_points; ++i) {
      const double u = -1.0 + 2.0 * i / (grid_points - 1);
      const Vec3 r = A - u * (B + u * C);
      f[j * grid_points + i] = dot(r, r);
    }
  }
}

// Steps 1-5 (kept out of line: its frame of grids and seeds would slow the fast path).
template <int Terms>
[[gnu::noinline]] ProjectionResult full_search(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                                               const ProjectionSettings& settings, ProjectionResult result,
                                               const Run& candidate) {
  // Step 5's outcome from the best descent: converged, and on an edge or a corner
  // with the gradient pointing out of the square.
  const auto finish_with = [&](const Run& best) {
    result.xi = best.xi;
    result.converged = best.converged;
    result.failure = best.converged ? FailureReason::none : FailureReason::max_iterations;
    result.on_boundary = pushed_out_of_square(s, best.xi, evaluate_local(s, ys, best.xi));
    return result;
  };
  std::array<double, grid_points * grid_points> f;  // every entry written by grid_values
  grid_values(s, ys, f);
  result.evaluations += grid_points * grid_points;

  // Seeds, (a): the grid's discrete local minima (no lower value among the up
  // to 8 neighbours; equal neighbours are both seeds).
  constexpr int n = grid_points;
  const auto coordinate = [](int i) { return -1.0 + 2.0 * i / (n - 1); };
  const auto less = [&f](int a, int b) { return f[a] < f[b] || (f[a] == f[b] && a < b); };
  // The least f over each point's 3 x 3 neighbourhood, by two separable passes
  // (branch-free); a point is a seed when it equals that least value.
  std::array<double, n * n> row_min;  // every entry written below
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int index = j * n + i;
      double m = f[index];
      if (i > 0) m = std::min(m, f[index - 1]);
      if (i < n - 1) m = std::min(m, f[index + 1]);
      row_min[index] = m;
    }
  }
  std::array<bool, n * n> seed_at;  // every entry written below
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int index = j * n + i;
      double m = row_min[index];
      if (j > 0) m = std::min(m, row_min[index - n]);
      if (j < n - 1) m = std::min(m, row_min[index + n]);
      seed_at[index] = f[index] <= m;
    }
  }
  // (b): on each edge, the discrete local minima along the edge where f
  // decreases out of the square (a constrained minimum on that edge may lie
  // in a sliver narrower than the grid, missed by (a)).
  for (int edge = 0; edge < 4; ++edge) {
    // edge 0: xi2 = -1, 1: xi1 = +1, 2: xi2 = +1, 3: xi1 = -1
    const auto index_of = [edge](int k) {
      switch (edge) {
        case 0:
          return k;
        case 1:
          return k * n + (n - 1);
        case 2:
          return (n - 1) * n + k;
        default:
          return k * n;
      }
    };
    for (int k = 0; k < n; ++k) {
      const int index = index_of(k);
      if (seed_at[index]) continue;
      if ((k > 0 && less(index_of(k - 1), index)) || (k < n - 1 && less(index_of(k + 1), index))) continue;
      const Xi xi{coordinate(index % n), coordinate(index / n)};
      const LocalGradient lg = evaluate_gradient(s, ys, xi);
      ++result.evaluations;
      const bool outward = edge == 0   ? lg.g[1] > 0.0
                           : edge == 1 ? lg.g[0] < 0.0
                           : edge == 2 ? lg.g[1] < 0.0
                                       : lg.g[0] > 0.0;
      seed_at[index] = outward;
    }
  }
  // Best first; at most max_seeds.
  struct Seed {
    double f;
    Xi xi;
  };
  std::array<Seed, max_seeds> seeds;  // the first seed_count entries are used
  int seed_count = 0;
  for (int index = 0; index < n * n; ++index) {
    if (!seed_at[index]) continue;
    const Seed seed{f[index], {coordinate(index % n), coordinate(index / n)}};
    int at = std::min(seed_count, max_seeds - 1);
    if (seed_count == max_seeds && !(seed.f < seeds[at].f)) continue;
    while (at > 0 && seed.f < seeds[at - 1].f) {
      seeds[at] = seeds[at - 1];
      --at;
    }
    seeds[at] = seed;
    seed_count = std::min(seed_count + 1, max_seeds);
  }
  // The caller's guess replaces the best seed when it is better.
  if (finite(xi0)) {
    const Xi guess = clamp_box(xi0);
    const double f_guess = evaluate_f(s, ys, guess);
    ++result.evaluations;
    if (f_guess < seeds[0].f) seeds[0] = {f_guess, guess};
  }

  RobustSearch<Terms> search(s, ys, settings, result);
  Run best{seeds[0].xi, std::numeric_limits<double>::infinity(), false};
  std::array<Xi, max_seeds + 2 * max_second_chances + 1> found;  // the first found_count entries
  int found_count = 0;
  // A candidate (Newton's point, a strict local minimum in the square) is the best so far. By (c)'s argument
  // below, a better minimum has a grid point with f < f_known + margin near it, so seeds
  // above that, or within 1.5 h of the candidate, need no descent of their own.
  double skip_above = std::numeric_limits<double>::infinity();
  constexpr double h = 2.0 / (n - 1);
  if (candidate.converged) {
    best = candidate;
    found[found_count++] = candidate.xi;
    const Local lc = evaluate_local(s, ys, candidate.xi);
    ++result.evaluations;
    skip_above = candidate.f + 0.5 * std::max(eigenvalues(lc.H)[1], lc.A.xx + lc.A.yy) * h * h;
  }
  for (int k = 0; k < seed_count; ++k) {
    if (candidate.converged &&
        (seeds[k].f >= skip_above || (std::fabs(seeds[k].xi[0] - candidate.xi[0]) <= 1.5 * h &&
                                      std::fabs(seeds[k].xi[1] - candidate.xi[1]) <= 1.5 * h)))
      continue;
    const Run run = search.descend(seeds[k].xi);
    found[found_count++] = run.xi;
    if (run.f < best.f) best = run;
  }
  // (c) second chance: a better minimum m missed by the seeds has a grid point
  // q within h / sqrt(2) (h the spacing) with f(q) <= f(m) + lambda h^2 / 4.
  // So descend also from every grid point with f < f_best + margin that is not
  // within 1.5 h of a point already found (lambda: twice the largest
  // eigenvalue of H at the best point, floored).
  {
    const Local lb = evaluate_local(s, ys, best.xi);
    ++result.evaluations;
    const double lambda = 2.0 * std::max(eigenvalues(lb.H)[1], lb.A.xx + lb.A.yy);
    const double margin = 0.25 * lambda * h * h;
    int extra = 0;
    // (d) an interior point found near an edge may hide a constrained minimum
    // on that edge beyond a ridge thinner than the grid: descend along each
    // edge within 1.5 h from the point's projection on it.
    // (e) Conversely, a point found on an edge may hide an interior minimum
    // just inside it: descend from the point moved h / 2 into the square.
    const int descents = found_count;
    for (int k = 0; k < descents; ++k) {
      for (int a = 0; a < 2 && extra < max_second_chances; ++a) {
        const double x = found[k][a];
        if (std::fabs(x) < 1.0 - 1.5 * h) continue;
        Xi q = found[k];
        Run run{q, 0.0, false};
        if (std::fabs(x) < 1.0) {  // (d)
          q[a] = x > 0.0 ? 1.0 : -1.0;
          run = search.descend_on_edge(q, a);
        } else {  // (e)
          q[a] = x > 0.0 ? 1.0 - 0.5 * h : -1.0 + 0.5 * h;
          run = search.descend(q);
        }
        found[found_count++] = run.xi;
        ++extra;
        if (run.f < best.f) best = run;
      }
    }
    for (int index = 0; index < n * n && extra < max_second_chances; ++index) {
      if (!(f[index] < best.f + margin)) continue;
      const Xi q{coordinate(index % n), coordinate(index / n)};
      bool known = false;
      for (int k = 0; k < found_count && !known; ++k)
        known = std::fabs(found[k][0] - q[0]) <= 1.5 * h && std::fabs(found[k][1] - q[1]) <= 1.5 * h;
      if (known) continue;
      const Run run = search.descend(q);
      found[found_count++] = run.xi;
      ++extra;
      if (run.f < best.f) best = run;
    }
  }
  return finish_with(best);
}

template <int Terms>
ProjectionResult robust_kernel(const Surface<Terms>& s, const Vec3& ys, Xi xi0,
                               const ProjectionSettings& settings) {
  ProjectionResult result;
  // 0a. Fast path: Newton from the guess and a proof that its point is the closest.
  Run newton_point{{0.0, 0.0}, std::numeric_limits<double>::infinity(), false};
  if (certified_newton(s, ys, finite(xi0) ? xi0 : Xi{0.0, 0.0}, settings, result, newton_point))
    return result;
  // 0b. f strictly convex on the square has one minimum there.
  if (convex_bound(s, ys) &&
      convex_newton(s, ys, finite(xi0) ? clamp_box(xi0) : Xi{0.0, 0.0}, settings, result)) {
    finish(s, ys, result);
    return result;
  }
  // Not proven convex, or the projected Newton stalled: the full search (its counts
  // add to the fast path's).
  result = full_search(s, ys, xi0, settings, result, newton_point);
  finish(s, ys, result);
  return result;
}

}  // namespace

namespace detail {
template <int Terms>
bool strictly_convex_on_square(const Surface<Terms>& s, const Vec3& ys) {
  return convex_bound(s, ys);
}
template bool strictly_convex_on_square<4>(const Surface<4>&, const Vec3&);
template bool strictly_convex_on_square<8>(const Surface<8>&, const Vec3&);
template <int Terms>
bool closest_point_proven(const Surface<Terms>& s, const Vec3& ys, Xi xi, double epsilon) {
  return closest_within(s, xi, evaluate_local(s, ys, xi), epsilon);
}
template bool closest_point_proven<4>(const Surface<4>&, const Vec3&, Xi, double);
template bool closest_point_proven<8>(const Surface<8>&, const Vec3&, Xi, double);
}  // namespace detail

ProjectionResult project_robust(const Segment& segment, const Vec3& point, Xi xi0,
                                const ProjectionSettings& settings) {
  return detail::dispatch<true>(segment, point, xi0, settings,
                                [](const auto& s, const Vec3& ys, Xi x, const ProjectionSettings& st) {
                                  return robust_kernel(s, ys, x, st);
                                });
}

}  // namespace exdyn::contact
