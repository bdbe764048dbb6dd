// The passes over the corners of the current configuration (element/corner_checks.hpp):
// the packed, threaded passes against the simple ones, element by element.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "box_mesh.hpp"
#include "common/parallel.hpp"
#include "element/corner_checks.hpp"
#include "element/element_block.hpp"
#include "element/hex8.hpp"
#include "element/hex8_constitutive.hpp"

namespace exdyn::element {
namespace {

const material::ElasticConstants steel = material::elastic_constants(210e9, 0.3, 7850.0);

// Boxes of unit bricks (box_mesh.hpp), x fastest: their x-rows make row packs, and the
// packs that straddle two rows do not.

// The stable step element by element, one lane: L_e(x) / c1.
CurrentStep simple_time_step(const ElementBlock& block, const NodalVectors& x_ref, const NodalVectors& u) {
  CurrentStep result{std::numeric_limits<double>::infinity(), 0};
  for (std::uint32_t e = 0; e < block.count; ++e) {
    ElementVectors x;
    for (int k = 0; k < 8; ++k) {
      const std::uint32_t n = block.connectivity[8 * std::size_t(e) + std::size_t(k)];
      x.x[k] = x_ref.x[n] + u.x[n], x.y[k] = x_ref.y[n] + u.y[n], x.z[k] = x_ref.z[n] + u.z[n];
    }
    const double dt = hex8::current_characteristic_length(x) / block.material.dilatational_wave_speed();
    if (dt < result.dt) result = {dt, block.first_element + e};
  }
  return result;
}

// A random state with nodes moved by up to `amplitude` (h = 1): from 0.3 on, some
// elements invert, at random places.
NodalVectors shaken(const Box& box, double amplitude, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  NodalVectors u(box.x_ref.size());
  for (std::size_t n = 0; n < u.size(); ++n)
    u.x[n] = amplitude * unit(rng), u.y[n] = amplitude * unit(rng), u.z[n] = amplitude * unit(rng);
  return u;
}

TEST(CornerChecks, PackedThreadedPassesAreTheSimpleOnesElementByElement) {
  // 37 x 5 x 6 = 1,110 bricks: three chunks (the last one partial), a last pack cut by
  // the block's end, row packs and packs across rows.
  const Box box = make_box(37, 5, 6, 1.0);
  const ElementBlock block = make_element_block(input::Formulation::hex8r, steel, 0.05, 100, box.count,
                                                box.connectivity.data(), box.x_ref);
  ASSERT_EQ(block.chunk_begin.size(), 4u);
  std::mt19937_64 rng(5);
  int found = 0, clean = 0;
  const int threads = max_threads();
  for (int trial = 0; trial < 60; ++trial) {
    const double amplitude = trial % 3 == 0 ? 0.1 : 0.22 + 0.002 * trial;
    const NodalVectors u = shaken(box, amplitude, rng);
    const InvertedElement simple = find_inverted_element(block, 0, block.count, box.x_ref, u);
    set_threads(1);
    const CornerChecks one = check_corners(block, box.x_ref, u);
    set_threads(2);
    const CornerChecks two = check_corners(block, box.x_ref, u);
    set_threads(threads);
    // The threads change nothing, to the bit.
    EXPECT_EQ(one.step.dt, two.step.dt);
    EXPECT_EQ(one.step.element, two.step.element);
    EXPECT_EQ(one.inverted.found, two.inverted.found);
    EXPECT_EQ(one.inverted.element, two.inverted.element);
    EXPECT_EQ(one.inverted.safety_radius, two.inverted.safety_radius);
    // Each pass alone gives what the pass of both gives.
    const CurrentStep step = current_time_step(block, box.x_ref, u);
    EXPECT_EQ(step.dt, one.step.dt);
    EXPECT_EQ(step.element, one.step.element);
    const InvertedElement inverted = find_inverted_element(block, box.x_ref, u);
    EXPECT_EQ(inverted.found, one.inverted.found);
    EXPECT_EQ(inverted.element, one.inverted.element);
    // The simple passes: the same element and corner (the packs may round the
    // determinants' products as fused multiply-adds).
    const CurrentStep reference = simple_time_step(block, box.x_ref, u);
    EXPECT_EQ(step.element, reference.element);
    EXPECT_NEAR(step.dt, reference.dt, 1e-13 * reference.dt);
    ASSERT_EQ(inverted.found, simple.found) << "trial " << trial;
    if (simple.found) {
      ++found;
      EXPECT_EQ(inverted.element, simple.element);
      EXPECT_EQ(inverted.corner, simple.corner);
      EXPECT_NEAR(inverted.det_jacobian, simple.det_jacobian, 1e-12 * std::abs(simple.det_jacobian) + 1e-15);
    } else {
      ++clean;
      EXPECT_NEAR(inverted.safety_radius, simple.safety_radius, 1e-12 * simple.safety_radius);
    }
  }
  EXPECT_GT(found, 5);  // both outcomes seen
  EXPECT_GT(clean, 5);
}

TEST(CornerChecks, TheLowestInvertedElementIsNamedWhicheverChunkHoldsIt) {
  // One node pushed through the one below it inverts the bricks under it: in the
  // second chunk (layer k = 4, elements 740-924), then in the first (k = 1).
  const Box box = make_box(37, 5, 6, 1.0);
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  for (const std::uint32_t node :
       {std::uint32_t(38 * 6 * 5 + 38 * 2 + 20), std::uint32_t(38 * 6 * 2 + 38 + 3)}) {
    NodalVectors u(box.x_ref.size());
    u.z[node] = -1.6;  // through the node below it
    const InvertedElement simple = find_inverted_element(block, 0, block.count, box.x_ref, u);
    ASSERT_TRUE(simple.found);
    for (const int threads : {1, 2}) {
      const int before = max_threads();
      set_threads(threads);
      const InvertedElement packed = find_inverted_element(block, box.x_ref, u);
      set_threads(before);
      EXPECT_TRUE(packed.found);
      EXPECT_EQ(packed.element, simple.element);
      EXPECT_EQ(packed.corner, simple.corner);
    }
  }
}

}  // namespace
}  // namespace exdyn::element
