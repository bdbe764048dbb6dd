// Segment geometry: shape functions, derivatives, normal.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/segment.hpp"
#include "random_cases.hpp"

namespace exdyn::contact {
namespace {

using testing::Distortion;
using testing::Random;

Vec3 interpolate_with_shape_functions(const Segment& s, Xi xi) {
  const auto N = shape_functions(s.type, xi);
  Vec3 y{};
  for (int i = 0; i < node_count(s.type); ++i) y = y + N[i] * s.nodes[i];
  return y;
}

TEST(Segment, ShapeFunctionsAreOneAtTheirNodeAndZeroAtTheOthers) {
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (int j = 0; j < node_count(type); ++j) {
      const auto N = shape_functions(type, node_xi[j]);
      for (int i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(N[i], i == j ? 1.0 : 0.0) << name(type) << " node " << j;
    }
  }
}

TEST(Segment, ShapeFunctionsSumToOne) {
  Random rng(1);
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (int k = 0; k < 100; ++k) {
      const auto N = shape_functions(type, {rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5)});
      double sum = 0.0;
      for (double n : N) sum += n;
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
  }
}

TEST(Segment, MonomialFormEqualsShapeFunctionInterpolation) {
  Random rng(2);
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (int k = 0; k < 200; ++k) {
      const Segment s = testing::random_segment(rng, type, Distortion::strong);
      const Xi xi{rng.uniform(-2, 2), rng.uniform(-2, 2)};
      const Vec3 a = position(s, xi), b = interpolate_with_shape_functions(s, xi);
      EXPECT_NEAR(a.x, b.x, 1e-13);
      EXPECT_NEAR(a.y, b.y, 1e-13);
      EXPECT_NEAR(a.z, b.z, 1e-13);
      const SurfacePoint p = evaluate(s, xi);
      EXPECT_EQ(p.y.x, a.x);
    }
  }
}

TEST(Segment, FirstAndSecondDerivativesMatchFiniteDifferences) {
  Random rng(3);
  const double h = 1e-5;
  const auto near = [](Vec3 a, Vec3 b, double tol) {
    return std::fabs(a.x - b.x) <= tol && std::fabs(a.y - b.y) <= tol && std::fabs(a.z - b.z) <= tol;
  };
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    for (int k = 0; k < 200; ++k) {
      const Segment s = testing::random_segment(rng, type, Distortion::strong);
      const Xi xi{rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2)};
      const SurfacePoint p = evaluate(s, xi);
      const auto at = [&](double du, double dv) { return evaluate(s, {xi[0] + du, xi[1] + dv}); };
      // Central differences: O(h^2) errors, exact for polynomials of degree <= 2 in each direction.
      const Vec3 a1 = (0.5 / h) * (at(h, 0).y - at(-h, 0).y);
      const Vec3 a2 = (0.5 / h) * (at(0, h).y - at(0, -h).y);
      EXPECT_TRUE(near(p.a1, a1, 1e-9)) << name(type);
      EXPECT_TRUE(near(p.a2, a2, 1e-9)) << name(type);
      EXPECT_TRUE(near(p.y11, (0.5 / h) * (at(h, 0).a1 - at(-h, 0).a1), 1e-9));
      EXPECT_TRUE(near(p.y22, (0.5 / h) * (at(0, h).a2 - at(0, -h).a2), 1e-9));
      EXPECT_TRUE(near(p.y12, (0.5 / h) * (at(0, h).a1 - at(0, -h).a1), 1e-9));
      EXPECT_TRUE(near(p.y12, (0.5 / h) * (at(h, 0).a2 - at(-h, 0).a2), 1e-9));
    }
  }
}

TEST(Segment, Quad8ReproducesTheQuadraticSurfaceOfT2Exactly) {
  // z = 0.5 x^2 + 0.1 y^2 at the nodes of the flat Q8.
  Segment s;
  s.type = SegmentType::quad8;
  for (int i = 0; i < 8; ++i) {
    const double x = node_xi[i][0], y = node_xi[i][1];
    s.nodes[i] = {x, y, 0.5 * x * x + 0.1 * y * y};
  }
  Random rng(4);
  for (int k = 0; k < 200; ++k) {
    const Xi xi{rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const SurfacePoint p = evaluate(s, xi);
    EXPECT_NEAR(p.y.x, xi[0], 1e-15);
    EXPECT_NEAR(p.y.y, xi[1], 1e-15);
    EXPECT_NEAR(p.y.z, 0.5 * xi[0] * xi[0] + 0.1 * xi[1] * xi[1], 1e-15);
    EXPECT_NEAR(p.a1.z, xi[0], 1e-15);
    EXPECT_NEAR(p.a2.z, 0.2 * xi[1], 1e-15);
    EXPECT_NEAR(p.y11.z, 1.0, 1e-15);
    EXPECT_NEAR(p.y22.z, 0.2, 1e-15);
    EXPECT_NEAR(p.y12.z, 0.0, 1e-15);
  }
}

TEST(Segment, NormalOfCounterClockwiseNodesPointsUp) {
  for (const SegmentType type : {SegmentType::quad4, SegmentType::quad8}) {
    Segment s;
    s.type = type;
    for (int i = 0; i < 8; ++i) s.nodes[i] = {2.0 * node_xi[i][0], 3.0 * node_xi[i][1], 1.0};
    const Vec3 n = outward_normal(s, {0.3, -0.4});
    EXPECT_NEAR(n.x, 0.0, 1e-15);
    EXPECT_NEAR(n.y, 0.0, 1e-15);
    EXPECT_NEAR(n.z, 1.0, 1e-15);
  }
}

TEST(Segment, NormalIsZeroWhereTheQuarterPointMapIsSingular) {
  Segment s;
  s.type = SegmentType::quad8;
  for (int i = 0; i < 8; ++i) s.nodes[i] = {node_xi[i][0], node_xi[i][1], 0.0};
  s.nodes[4] = {-0.5, -1, 0};
  s.nodes[7] = {-1, -0.5, 0};
  const SurfacePoint p = evaluate(s, {-1, -1});
  EXPECT_NEAR(norm(p.a1), 0.0, 1e-15);
  EXPECT_NEAR(norm(p.a2), 0.0, 1e-15);
  const Vec3 n = outward_normal(s, {-1, -1});
  EXPECT_EQ(norm(n), 0.0);
}

TEST(Segment, SizeIsTheBoundingBoxDiagonal) {
  Segment s;
  s.type = SegmentType::quad4;
  for (int i = 0; i < 4; ++i) s.nodes[i] = {node_xi[i][0], node_xi[i][1], 0.0};
  EXPECT_DOUBLE_EQ(segment_size(s), std::sqrt(8.0));
}

}  // namespace
}  // namespace exdyn::contact
