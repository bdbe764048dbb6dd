// The bucket search must find exactly the brute-force candidate set.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <random>

#include "contact/bucket_search.hpp"

namespace {

using exdyn::NodalVectors;
using exdyn::contact::Box;
using exdyn::contact::CandidatePair;
using Quad = std::array<std::uint32_t, 4>;

auto position_in(const NodalVectors& x) {
  return [&x](std::uint32_t node) { return std::array<double, 3>{x.x[node], x.y[node], x.z[node]}; };
}

// A distorted, curved n x n surface of quads (nodes 0 .. (n+1)^2 - 1).
struct Surface {
  NodalVectors x;
  std::vector<Quad> quads;
};

Surface random_surface(int n, double h, double distortion, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-distortion * h, distortion * h);
  Surface s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      s.x.x.push_back(i * h + jitter(rng));
      s.x.y.push_back(j * h + jitter(rng));
      s.x.z.push_back(0.3 * h * std::sin(0.7 * i) * std::cos(0.4 * j) + jitter(rng));
    }
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) s.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return s;
}

NodalVectors random_points(std::size_t count, double lo, double hi, double z_spread, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(lo, hi), w(-z_spread, z_spread);
  NodalVectors p;
  for (std::size_t i = 0; i < count; ++i) {
    p.x.push_back(u(rng));
    p.y.push_back(u(rng));
    p.z.push_back(w(rng));
  }
  return p;
}

TEST(BucketSearch, FindsExactlyTheBruteForceSetOnRandomDistortedSurfaces) {
  std::mt19937 rng(12345);
  exdyn::contact::BucketWorkspace workspace;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 3 + trial % 17;
    const double h = 0.1 * (1 + trial % 3);
    const Surface surface = random_surface(n, h, 0.05 * (trial % 5), rng);
    const NodalVectors points = random_points(50 + 37 * trial, -0.5 * h, (n + 0.5) * h, 0.6 * h, rng);
    std::vector<Box> boxes;
    exdyn::contact::segment_boxes(position_in(surface.x), surface.quads, 0.1 * h * (trial % 4), boxes);
    std::vector<CandidatePair> fast, reference;
    const double cell = trial % 2 ? 0.0 : h * (0.3 + 0.2 * (trial % 7));  // automatic and chosen cells
    exdyn::contact::bucket_search(points, boxes, cell, workspace, fast);
    exdyn::contact::brute_force_search(points, boxes, reference);
    ASSERT_EQ(fast, reference) << "trial " << trial;  // same pairs, same order
    if (trial > 4) {
      EXPECT_FALSE(reference.empty());
    }
  }
}

TEST(BucketSearch, HandlesPointsOnCellBoundariesAndFlatSurfaces) {
  // A flat grid of points exactly on the corners of a flat grid of quads: every
  // point touches up to four boxes, with zero capture distance.
  std::mt19937 rng(7);
  const Surface surface = random_surface(10, 1.0, 0.0, rng);
  NodalVectors flat = surface.x;
  std::fill(flat.z.begin(), flat.z.end(), 0.0);
  std::vector<Quad> quads = surface.quads;
  std::vector<Box> boxes;
  exdyn::contact::segment_boxes(position_in(flat), quads, 0.0, boxes);
  std::vector<CandidatePair> fast, reference;
  exdyn::contact::BucketWorkspace workspace;
  for (double cell : {0.0, 1.0, 0.5, 3.0}) {
    exdyn::contact::bucket_search(flat, boxes, cell, workspace, fast);
    exdyn::contact::brute_force_search(flat, boxes, reference);
    ASSERT_EQ(fast, reference) << "cell " << cell;
    // interior corner nodes touch 4 quads, edge nodes 2, corners 1: 4 per quad in all
    EXPECT_EQ(fast.size(), 4 * quads.size());
  }
}

TEST(BucketSearch, FindsTheBruteForceSetWhileTheSurfacesMove) {
  // Points and surface move independently each step; the search is redone every
  // step on the current coordinates and must always agree with brute force.
  std::mt19937 rng(99);
  Surface surface = random_surface(12, 0.2, 0.1, rng);
  NodalVectors points = random_points(800, -0.2, 2.6, 0.15, rng);
  std::normal_distribution<double> step(0.0, 0.01);
  exdyn::contact::BucketWorkspace workspace;
  std::vector<Box> boxes;
  std::vector<CandidatePair> fast, reference;
  for (int s = 0; s < 50; ++s) {
    for (auto* field : {&surface.x, &points})
      for (int c = 0; c < 3; ++c)
        for (double& v : field->component(c)) v += step(rng);
    exdyn::contact::segment_boxes(position_in(surface.x), surface.quads, 0.05, boxes);
    exdyn::contact::bucket_search(points, boxes, 0.0, workspace, fast);
    exdyn::contact::brute_force_search(points, boxes, reference);
    ASSERT_EQ(fast, reference) << "step " << s;
  }
}

TEST(BucketSearch, EmptyInputsGiveNoPairs) {
  exdyn::contact::BucketWorkspace workspace;
  std::vector<CandidatePair> pairs{{1, 2}};
  exdyn::contact::bucket_search(NodalVectors{}, {Box{}}, 0.0, workspace, pairs);
  EXPECT_TRUE(pairs.empty());
  NodalVectors one(1);
  exdyn::contact::bucket_search(one, {}, 0.0, workspace, pairs);
  EXPECT_TRUE(pairs.empty());
}

}  // namespace
