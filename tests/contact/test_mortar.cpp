// Mortar segmentation (contact/mortar.hpp): the triangle rules, polygon clipping, and
// the pieces' points against exact integrals: on flat non-matching faces the points
// integrate the consistent forces of a uniform pressure on both sides exactly; on a
// curved 8-node segment their weights add up to its true area.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "contact/mortar.hpp"
#include "contact/quadrature.hpp"

namespace exdyn::contact {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Integral of x^a y^b over the triangle (0,0) (1,0) (0,1): a! b! / (a + b + 2)!.
double monomial_integral(int a, int b) { return factorial(a) * factorial(b) / factorial(a + b + 2); }

double rule_integral(const PieceRule& rule, int a, int b) {
  double sum = 0.0;
  for (int g = 0; g < rule.count; ++g) {
    // Barycentric (l0, l1, l2) at the corners (0,0), (1,0), (0,1): x = l1, y = l2.
    const double x = rule.point[std::size_t(g)][1], y = rule.point[std::size_t(g)][2];
    sum += rule.weight[std::size_t(g)] * 0.5 * std::pow(x, a) * std::pow(y, b);
  }
  return sum;
}

TEST(PieceRule, EachTriangleRuleIsExactToItsDegreeAndNoFurther) {
  const std::array<std::pair<int, int>, 4> rules{{{1, 1}, {3, 2}, {6, 4}, {7, 5}}};
  for (const auto& [points, degree] : rules) {
    const PieceRule rule = piece_rule(points);
    ASSERT_EQ(rule.count, points);
    double weights = 0.0;
    for (int g = 0; g < rule.count; ++g) {
      weights += rule.weight[std::size_t(g)];
      const auto& l = rule.point[std::size_t(g)];
      EXPECT_NEAR(l[0] + l[1] + l[2], 1.0, 1e-15);
    }
    EXPECT_NEAR(weights, 1.0, 1e-15);
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        EXPECT_NEAR(rule_integral(rule, a, b), monomial_integral(a, b), 1e-15)
            << points << " points, x^" << a << " y^" << b;
    double worst = 0.0;  // degree + 1 is not integrated exactly by every monomial
    for (int a = 0; a <= degree + 1; ++a)
      worst = std::max(
          worst, std::abs(rule_integral(rule, a, degree + 1 - a) - monomial_integral(a, degree + 1 - a)));
    EXPECT_GT(worst, 1e-6) << points << " points";
  }
}

Polygon rectangle(double x0, double y0, double x1, double y1) {
  Polygon p;
  p.count = 4;
  p.vertex = {Vec2{x0, y0}, Vec2{x1, y0}, Vec2{x1, y1}, Vec2{x0, y1}};
  return p;
}

TEST(Clipping, OverlapOfRectanglesIsTheirIntersection) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    double a[4] = {u(rng), u(rng), u(rng), u(rng)}, b[4] = {u(rng), u(rng), u(rng), u(rng)};
    if (a[0] > a[2]) std::swap(a[0], a[2]);
    if (a[1] > a[3]) std::swap(a[1], a[3]);
    if (b[0] > b[2]) std::swap(b[0], b[2]);
    if (b[1] > b[3]) std::swap(b[1], b[3]);
    const double w = std::max(0.0, std::min(a[2], b[2]) - std::max(a[0], b[0]));
    const double h = std::max(0.0, std::min(a[3], b[3]) - std::max(a[1], b[1]));
    const Polygon piece = clip_convex(rectangle(a[0], a[1], a[2], a[3]), rectangle(b[0], b[1], b[2], b[3]));
    EXPECT_NEAR(piece.count > 0 ? signed_area(piece) : 0.0, w * h, 1e-14);
  }
}

TEST(Clipping, ASquareTurnedOnAnotherIsAnOctagonOfTheKnownArea) {
  // A unit square turned 45 degrees about the centre of another: 8 vertices, area
  // 1 - 4 corner triangles of legs (sqrt 2 - 1) / sqrt 2 ... = 2 (sqrt 2 - 1).
  const double r = std::sqrt(0.5);
  Polygon turned;
  turned.count = 4;
  turned.vertex = {Vec2{0.0, -r}, Vec2{r, 0.0}, Vec2{0.0, r}, Vec2{-r, 0.0}};
  const Polygon piece = clip_convex(rectangle(-0.5, -0.5, 0.5, 0.5), turned);
  EXPECT_EQ(piece.count, 8);
  EXPECT_NEAR(signed_area(piece), 2.0 * (std::sqrt(2.0) - 1.0), 1e-15);
  EXPECT_TRUE(is_convex(piece));
}

Segment flat_segment(SegmentType type, double x0, double y0, double x1, double y1, double z,
                     bool facing_down) {
  Segment s;
  s.type = type;
  std::array<Xi, 8> corners;
  for (int i = 0; i < 8; ++i) corners[std::size_t(i)] = node_xi[std::size_t(i)];
  for (int i = 0; i < node_count(type); ++i) {
    const double u = 0.5 * (1 + corners[std::size_t(i)][0]), v = 0.5 * (1 + corners[std::size_t(i)][1]);
    // Facing down (-z): the same nodes with y mirrored in xi2 (corners clockwise from above).
    const double y = facing_down ? y1 - v * (y1 - y0) : y0 + v * (y1 - y0);
    s.nodes[std::size_t(i)] = {x0 + u * (x1 - x0), y, z};
  }
  return s;
}

// The exact integral of a master segment's shape function N_J over the part of a
// rectangle it covers, by 4 x 4 Gauss points on the intersection (N_J is of degree
// at most 3 in each direction there).
double master_integral(const Segment& master, int J, double x0, double y0, double x1, double y1) {
  const Vec3 lo = master.nodes[0], hi = master.nodes[2];
  const double mx0 = std::min(lo.x, hi.x), mx1 = std::max(lo.x, hi.x), my0 = std::min(lo.y, hi.y),
               my1 = std::max(lo.y, hi.y);
  const double ax = std::max(x0, mx0), bx = std::min(x1, mx1), ay = std::max(y0, my0), by = std::min(y1, my1);
  if (!(bx > ax && by > ay)) return 0.0;
  const GaussLegendre g = gauss_legendre(4);
  double sum = 0.0;
  for (int i = 0; i < g.count; ++i)
    for (int j = 0; j < g.count; ++j) {
      const double x = 0.5 * (ax + bx) + 0.5 * (bx - ax) * g.abscissa[std::size_t(i)];
      const double y = 0.5 * (ay + by) + 0.5 * (by - ay) * g.abscissa[std::size_t(j)];
      // xi of (x, y) on the master (its node 0 at (lo.x, lo.y), xi1 along x, xi2 along y or -y).
      const Xi xi{-1.0 + 2.0 * (x - lo.x) / (hi.x - lo.x), -1.0 + 2.0 * (y - lo.y) / (hi.y - lo.y)};
      sum += g.weight[std::size_t(i)] * g.weight[std::size_t(j)] * 0.25 * (bx - ax) * (by - ay) *
             shape_functions(master.type, xi)[std::size_t(J)];
    }
  return sum;
}

// A flat slave segment over a grid of master segments that it does not match (the
// master grid finer, shifted): every slave node's sum of w N_I is its consistent area
// integral N_I dA, every master node's sum of w N_J(xi_master) the integral of N_J over
// the slave segment, and the weights add up to the slave's area.
void check_consistent_forces(SegmentType slave_type, SegmentType master_type, int rule_points) {
  const double x0 = 0.1, y0 = -0.2, x1 = 1.3, y1 = 0.9;  // the slave rectangle, z = 0
  const Segment slave = flat_segment(slave_type, x0, y0, x1, y1, 0.0, false);
  const PieceRule rule = piece_rule(rule_points);
  std::array<double, 8> slave_sum{};
  double area = 0.0;
  const int n = 5;
  const double mx0 = -0.13, my0 = -0.31, step = 0.37;  // master grid of 5 x 5 covering the slave
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double ax = mx0 + i * step, ay = my0 + j * step;
      // Master facing down, 1e-4 below the slave (a gap).
      const Segment master = flat_segment(master_type, ax, ay, ax + step, ay + step, -1e-4, true);
      std::vector<MortarPoint> points(max_mortar_points_per_pair);
      const int count = mortar_points(slave, master, rule, 1.0, points.data());
      std::array<double, 8> master_sum{};
      for (int k = 0; k < count; ++k) {
        const MortarPoint& p = points[std::size_t(k)];
        area += p.weight;
        const auto Ns = shape_functions(slave_type, p.slave_xi),
                   Nm = shape_functions(master_type, p.master_xi);
        for (int a = 0; a < 8; ++a) slave_sum[std::size_t(a)] += p.weight * Ns[std::size_t(a)];
        for (int a = 0; a < 8; ++a) master_sum[std::size_t(a)] += p.weight * Nm[std::size_t(a)];
      }
      // The master's xi runs along +x and -y from its node 0 at (ax, ay + step).
      for (int J = 0; J < node_count(master_type); ++J)
        EXPECT_NEAR(master_sum[std::size_t(J)], master_integral(master, J, x0, y0, x1, y1), 1e-14)
            << "master " << i << "," << j << " node " << J;
    }
  const double A = (x1 - x0) * (y1 - y0);
  EXPECT_NEAR(area, A, 1e-14);
  for (int I = 0; I < node_count(slave_type); ++I) {
    // Integral N_I dA: A/4 on quad4; -A/12 at the corners, A/3 at the mid-sides of quad8.
    const double exact = slave_type == SegmentType::quad4 ? A / 4 : (I < 4 ? -A / 12 : A / 3);
    EXPECT_NEAR(slave_sum[std::size_t(I)], exact, 1e-14) << "slave node " << I;
  }
}

TEST(MortarPoints, FlatQuad4OnANonMatchingGridIntegratesBothSidesExactly) {
  check_consistent_forces(SegmentType::quad4, SegmentType::quad4, 3);
}

TEST(MortarPoints, FlatQuad8OnANonMatchingGridIntegratesBothSidesExactly) {
  check_consistent_forces(SegmentType::quad8, SegmentType::quad8, 6);
  check_consistent_forces(SegmentType::quad4, SegmentType::quad8, 6);
  check_consistent_forces(SegmentType::quad8, SegmentType::quad4, 6);
}

TEST(MortarPoints, OnPiecesOfManyCornersTheRulesOfDegreeTwoAgreeAndTheCentroidDoesNot) {
  // A master turned 30 degrees over the slave: pieces of 3 to 8 corners, cut into fans of
  // triangles. A master shape function (bilinear: degree 2 on a flat face) integrates
  // alike with 3, 6 and 7 points a triangle; the centroid alone (degree 1) misses it, so
  // the exactness checks above can fail.
  const Segment slave = flat_segment(SegmentType::quad4, 0.0, 0.0, 1.0, 1.0, 0.0, false);
  Segment master;
  master.type = SegmentType::quad4;
  const double c = std::cos(0.5236), s = std::sin(0.5236);
  const std::array<std::array<double, 2>, 4> corners{{{-0.4, 0.4}, {0.4, 0.4}, {0.4, -0.4}, {-0.4, -0.4}}};
  for (int i = 0; i < 4; ++i)  // facing down: clockwise from above
    master.nodes[std::size_t(i)] = {0.6 + c * corners[std::size_t(i)][0] - s * corners[std::size_t(i)][1],
                                    0.5 + s * corners[std::size_t(i)][0] + c * corners[std::size_t(i)][1],
                                    -1e-4};
  std::array<double, 4> integral{};
  for (int k = 0; k < 4; ++k) {
    const int rule = std::array<int, 4>{1, 3, 6, 7}[std::size_t(k)];
    std::vector<MortarPoint> points(max_mortar_points_per_pair);
    const int count = mortar_points(slave, master, piece_rule(rule), 1.0, points.data());
    EXPECT_GT(count, 0);
    for (int i = 0; i < count; ++i)
      integral[std::size_t(k)] += points[std::size_t(i)].weight *
                                  shape_functions(SegmentType::quad4, points[std::size_t(i)].master_xi)[0];
  }
  EXPECT_NEAR(integral[2], integral[1], 1e-15);
  EXPECT_NEAR(integral[3], integral[1], 1e-15);
  EXPECT_GT(std::abs(integral[0] - integral[1]), 1e-4);
}

// The area of a patch of a sphere of radius 1 (its 8 nodes on it), its pole down, that
// the weights of the mortar points on a flat master under it add up to, against the
// patch's area integral |a1 x a2| dxi (6 x 6 Gauss points): the relative error.
double curved_area_error(double half_angle, int points_per_triangle) {
  Segment slave;
  slave.type = SegmentType::quad8;
  for (int i = 0; i < 8; ++i) {
    const double a = half_angle * node_xi[std::size_t(i)][0], b = -half_angle * node_xi[std::size_t(i)][1];
    const Vec3 d{std::tan(a), std::tan(b), -1.0};
    slave.nodes[std::size_t(i)] = (1.0 / norm(d)) * d;  // outward normal of the patch: down
  }
  const Segment master = flat_segment(SegmentType::quad4, -1.0, -1.0, 1.0, 1.0, -1.0 - 1e-3, false);
  const GaussLegendre g = gauss_legendre(6);
  double exact = 0.0;
  for (int i = 0; i < g.count; ++i)
    for (int j = 0; j < g.count; ++j) {
      const SurfacePoint p = evaluate(slave, {g.abscissa[std::size_t(i)], g.abscissa[std::size_t(j)]});
      exact += g.weight[std::size_t(i)] * g.weight[std::size_t(j)] * norm(cross(p.a1, p.a2));
    }
  std::vector<MortarPoint> points(max_mortar_points_per_pair);
  const int count = mortar_points(slave, master, piece_rule(points_per_triangle), 1.0, points.data());
  double area = 0.0;
  for (int k = 0; k < count; ++k) area += points[std::size_t(k)].weight;
  return std::abs(area / exact - 1.0);
}

TEST(MortarPoints, ACurvedQuad8OnAFlatMasterWeighsItsTrueArea) {
  // The weights integrate |a1 x a2| / |det dq/dxi|, smooth but not a polynomial: the
  // error of the rule falls fast with the segment's angle. A segment of the Hertz ball
  // spans 90 / 16 = 5.6 degrees; this one 40 degrees, then 5.7.
  for (int points : {6, 7}) {
    const double large = curved_area_error(0.35, points), small = curved_area_error(0.05, points);
    std::printf("curved quad8, %d points a triangle: area error %.1e at 40 degrees, %.1e at 5.7\n", points,
                large, small);
    EXPECT_LE(large, 2e-5);
    EXPECT_LE(small, 1e-9);
  }
}

TEST(MortarPoints, NoPiecesFromAMasterNotFacingOrBeyondTheCapture) {
  const Segment slave = flat_segment(SegmentType::quad4, 0, 0, 1, 1, 0.0, false);  // normal +z
  std::vector<MortarPoint> points(max_mortar_points_per_pair);
  const PieceRule rule = piece_rule(3);
  // Facing the same way (a master whose normal is +z too): nothing.
  EXPECT_EQ(mortar_points(slave, flat_segment(SegmentType::quad4, 0, 0, 1, 1, 0.01, false), rule, 1.0,
                          points.data()),
            0);
  // Facing, 0.01 above: pieces within a capture of 0.02, none within 0.005.
  const Segment above = flat_segment(SegmentType::quad4, 0, 0, 1, 1, 0.01, true);
  EXPECT_EQ(mortar_points(slave, above, rule, 0.02, points.data()), 4);  // 2 x 2 Gauss points
  EXPECT_EQ(mortar_points(slave, above, rule, 0.005, points.data()), 0);
}

}  // namespace
}  // namespace exdyn::contact
