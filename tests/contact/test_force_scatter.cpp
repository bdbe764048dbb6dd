// The chunked scatter of a pass's point forces (contact/force_scatter.hpp) against the
// simple one in slave point order: the same bits, on 1 and 2 threads, for slave nodes
// and for Gauss points of slave segments, on surfaces whose points land on master
// segments in any order (so that consecutive chunks share nodes), slave and master
// sides sharing nodes too. And the records carry the same values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "common/parallel.hpp"
#include "contact/force_scatter.hpp"

namespace {

using namespace exdyn;
using namespace exdyn::contact;

// A master grid of g x g four-node segments on nodes 0 .. (g + 1)^2 - 1, and a pass of
// `points` slave points: nodes (each a node of the grid or past it) or Gauss points of
// slave segments (segments of the same grid); each point in contact with a random
// segment at a random xi, gap, normal and force, or not.
struct Scene {
  ContactSurfaces surfaces;
  ContactPassState state;
  std::size_t nodes = 0;
};

Scene random_scene(bool quadrature, std::size_t points, std::mt19937_64& rng) {
  const std::uint32_t g = 12, row = g + 1;
  Scene scene;
  scene.nodes = std::size_t(row) * row + 40;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<std::uint32_t> segment_of(0, g * g - 1);
  for (std::uint32_t j = 0; j < g; ++j)
    for (std::uint32_t i = 0; i < g; ++i) {
      SegmentNodes s;
      const std::uint32_t a = i + row * j;
      s.nodes = {a, a + 1, a + 1 + row, a + row};
      scene.surfaces.segments.push_back(s);
    }
  scene.surfaces.quadrature = quadrature;
  if (quadrature) {
    scene.surfaces.slave_segments = scene.surfaces.segments;
    for (std::size_t p = 0; p < points; ++p)
      scene.surfaces.quadrature_points.push_back({segment_of(rng), {unit(rng), unit(rng)}, 0.1});
  } else {
    // Ascending distinct nodes, some of them master nodes too.
    std::vector<std::uint32_t> all(scene.nodes);
    for (std::uint32_t n = 0; n < all.size(); ++n) all[n] = n;
    std::shuffle(all.begin(), all.end(), rng);
    all.resize(std::min(points, all.size()));
    std::sort(all.begin(), all.end());
    scene.surfaces.slave_nodes = all;
  }
  // The pass's nodes: its slave and master nodes, ascending.
  std::vector<std::uint32_t>& moving = scene.surfaces.moving_nodes;
  moving = scene.surfaces.slave_nodes;
  for (std::uint32_t k = 0; k < row * row; ++k) moving.push_back(k);
  std::sort(moving.begin(), moving.end());
  moving.erase(std::unique(moving.begin(), moving.end()), moving.end());
  const std::size_t n = scene.surfaces.point_count();
  scene.state.contacts.resize(n);
  scene.state.point_force.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    auto& c = scene.state.contacts[p];
    if (unit(rng) < -0.8) continue;  // no contact
    c.segment = std::int64_t(segment_of(rng));
    c.xi = {unit(rng), unit(rng)};
    c.gap = unit(rng) < -0.6 ? 0.25 * (unit(rng) + 1.0) : -1e-3 * (unit(rng) + 1.5);  // open or pressed
    const Vec3 n3{unit(rng), unit(rng), 1.0};
    c.normal = (1.0 / norm(n3)) * n3;
    if (c.gap < 0.0) scene.state.point_force[p] = Vec3{unit(rng), unit(rng), 1e3 * (unit(rng) + 2.0)};
  }
  return scene;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Force and gap arrays with values already in them (the passes before this one).
void fill(NodalVectors& force, std::vector<double>& gap, std::size_t nodes) {
  force = NodalVectors(nodes);
  gap.assign(nodes, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < nodes; ++i) {
    force.x[i] = 1e-3 * double(i), force.y[i] = -2e-3 * double(i), force.z[i] = 0.1 / double(i + 1);
    if (i % 7 == 0) gap[i] = 1e-4;
  }
}

TEST(ForceScatter, ChunksOnTheThreadsGiveThePointOrdersBits) {
  std::mt19937_64 rng(11);
  const int threads = max_threads();
  int shared = 0;  // scenes whose chunks share nodes (the ordered phase did work)
  for (int trial = 0; trial < 24; ++trial) {
    const bool quadrature = trial % 2 == 1;
    Scene scene = random_scene(quadrature, 150 + 37 * std::size_t(trial), rng);
    NodalVectors reference;
    std::vector<double> reference_gap;
    fill(reference, reference_gap, scene.nodes);
    scatter_in_point_order(scene.surfaces, scene.state, reference, reference_gap);
    for (const int t : {1, 2}) {
      for (const std::size_t chunk : {std::size_t(16), std::size_t(64)}) {
        set_threads(t);
        NodalVectors force;
        std::vector<double> gap;
        fill(force, gap, scene.nodes);
        scatter_by_chunks(scene.surfaces, scene.state, force, gap, chunk, scene.state.scatter);
        set_threads(threads);
        EXPECT_TRUE(same_bits(force.x, reference.x) && same_bits(force.y, reference.y) &&
                    same_bits(force.z, reference.z))
            << "trial " << trial << ", " << t << " threads, chunks of " << chunk;
        EXPECT_TRUE(same_bits(gap, reference_gap)) << "trial " << trial;
        for (const auto& late : scene.state.scatter.late) shared += late.empty() ? 0 : 1;
      }
    }
  }
  EXPECT_GT(shared, 100);  // the ordered phase ran, on most chunks
}

TEST(ForceScatter, RecordsCarryThePointOrdersValues) {
  std::mt19937_64 rng(3);
  for (const bool quadrature : {false, true}) {
    Scene scene = random_scene(quadrature, 300, rng);
    std::vector<std::uint64_t> keys(scene.surfaces.point_count());
    for (std::size_t p = 0; p < keys.size(); ++p) keys[p] = p;
    RecordSink sink;
    sink.point_keys = &keys;
    scatter_to_records(scene.surfaces, scene.state, sink);
    // The records added at their nodes in key order: the point order's sums.
    std::stable_sort(sink.records.begin(), sink.records.end(),
                     [](const ForceRecord& a, const ForceRecord& b) { return a.key < b.key; });
    NodalVectors from_records, reference;
    std::vector<double> gap_from_records, reference_gap;
    fill(from_records, gap_from_records, scene.nodes);
    fill(reference, reference_gap, scene.nodes);
    for (const ForceRecord& r : sink.records) {
      if (r.kind == ForceRecord::gap) {
        gap_from_records[r.node] = std::min(gap_from_records[r.node], r.value[0]);
        continue;
      }
      from_records.x[r.node] += r.value[0];
      from_records.y[r.node] += r.value[1];
      from_records.z[r.node] += r.value[2];
    }
    scatter_in_point_order(scene.surfaces, scene.state, reference, reference_gap);
    EXPECT_TRUE(same_bits(from_records.x, reference.x) && same_bits(from_records.y, reference.y) &&
                same_bits(from_records.z, reference.z));
    EXPECT_TRUE(same_bits(gap_from_records, reference_gap));
  }
}

}  // namespace
