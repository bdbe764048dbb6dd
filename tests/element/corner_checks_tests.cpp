// The passes over the corners of the current configuration (element/corner_checks.hpp):
// the packed, threaded passes against the simple ones, element by element.
#include <gtest/gtest.h>

#include <algorithm>
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
#include "material/material_law.hpp"

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

// Finite-strain steel with linear hardening that fails at a plastic strain of 0.5.
material::MaterialLaw failing_law() {
  material::MaterialLaw law;
  law.finite = true;
  law.flow = material::FlowRule::hardening, law.hardening = material::Hardening::linear(400e6, 100e6);
  law.failure.model = input::FailureModel::plastic_strain, law.failure.strain = 0.5;
  return law;
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

TEST(CornerChecks, TheClosedFormVolumeIsTheGaussSumOfDetJ) {
  // Bricks of side 1 with every corner moved by up to 0.3: the length of the current
  // configuration (closed-form volume, on one element and in the 8 lanes of a pack)
  // against characteristic_length (2 x 2 x 2 Gauss sum of det J), to round-off.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  BasicElementVectors<Pack<8>> pack{BasicElementVectors<Pack<8>>::Uninitialized{}};
  ElementVectors bricks[8];
  for (int trial = 0; trial < 200; ++trial) {
    ElementVectors& x = bricks[trial % 8];
    for (int k = 0; k < 8; ++k) {
      const Vector3& s = hex8::node_natural_coordinates[std::size_t(k)];
      x.x[k] = 0.5 * s[0] + 0.3 * unit(rng), x.y[k] = 0.5 * s[1] + 0.3 * unit(rng),
      x.z[k] = 0.5 * s[2] + 0.3 * unit(rng);
      pack.x[k][trial % 8] = x.x[k], pack.y[k][trial % 8] = x.y[k], pack.z[k][trial % 8] = x.z[k];
    }
    const double gauss = hex8::characteristic_length(x);
    EXPECT_NEAR(hex8::current_characteristic_length(x), gauss, 1e-14 * gauss) << "trial " << trial;
    if (trial % 8 != 7) continue;
    const Pack<8> lanes = hex8::current_characteristic_length(pack);
    for (int lane = 0; lane < 8; ++lane)
      EXPECT_NEAR(lanes[lane], hex8::characteristic_length(bricks[lane]), 1e-14 * lanes[lane]);
  }
  // The unit cube, exactly.
  ElementVectors cube;
  for (int k = 0; k < 8; ++k) {
    const Vector3& s = hex8::node_natural_coordinates[std::size_t(k)];
    cube.x[k] = 0.5 * (s[0] + 1.0), cube.y[k] = 0.5 * (s[1] + 1.0), cube.z[k] = 0.5 * (s[2] + 1.0);
  }
  EXPECT_EQ(hex8::current_characteristic_length(cube), 1.0);
}

// The checks the element pass of a law's 8-node loop runs on the corners it gathers
// (request_corner_checks) are the pass over the corners alone, to the bit: steps,
// inverted elements and safety radii, on 1 and 2 threads, with row packs and packs
// across rows, some states with inverted elements.
TEST(CornerChecks, TheElementPassRunsThemToTheBitOfTheCornerPass) {
  const Box box = make_box(37, 5, 6, 1.0);
  material::MaterialLaw law;
  law.finite = true;
  law.flow = material::FlowRule::hardening, law.hardening = material::Hardening::linear(400e6, 100e6);
  const int threads = max_threads();
  int found = 0;
  for (const input::Formulation formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const ElementBlock block =
        make_element_block(formulation, steel, 0.05, 100, box.count, box.connectivity.data(), box.x_ref, law);
    ASSERT_TRUE(block.corners_in_pass);
    set_material_time_step(block, 1e-7);
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 24; ++trial) {
      const NodalVectors u = shaken(box, 0.05 + 0.0125 * trial, rng);
      const bool step = trial % 3 != 1, inversion = trial % 3 != 2;
      for (const int t : {1, 2}) {
        set_threads(t);
        NodalVectors f(box.x_ref.size());
        request_corner_checks(block, box.x_ref, step, inversion);
        add_internal_forces(block, u, f, nullptr);
        const CornerChecks fused = corner_checks_of_pass(block);
        EXPECT_EQ(block.corner_request.x_ref, nullptr);  // the request is served once
        const CornerChecks alone = check_corners(block, box.x_ref, u);
        if (step) {
          EXPECT_EQ(fused.step.dt, alone.step.dt) << "trial " << trial;
          EXPECT_EQ(fused.step.element, alone.step.element);
        }
        if (inversion) {
          EXPECT_EQ(fused.inverted.found, alone.inverted.found) << "trial " << trial;
          EXPECT_EQ(fused.inverted.element, alone.inverted.element);
          EXPECT_EQ(fused.inverted.corner, alone.inverted.corner);
          EXPECT_EQ(fused.inverted.safety_radius, alone.inverted.safety_radius);
          found += alone.inverted.found && t == 1 ? 1 : 0;
        }
      }
    }
  }
  set_threads(threads);
  EXPECT_GT(found, 2);  // inverted states seen
}

// time.erode (element_block.hpp, ElementFailure::erode_step): the corner passes mark
// every live element whose own step is below the limit or that has a corner det J <= 0,
// exactly the elements the simple element-by-element checks name, on any number of
// threads and in the element pass as in the pass of its own; the marked ones set no
// step and are not reported inverted.
TEST(CornerChecks, TimeErodeMarksTheElementsTheSimpleChecksNameAndLeavesThemOut) {
  const Box box = make_box(37, 5, 6, 1.0);
  const material::MaterialLaw law = failing_law();
  const double c1 = steel.dilatational_wave_speed();
  const double limit = 0.75 / c1;  // 3/4 of an undeformed unit brick's L_e / c1
  const int threads = max_threads();
  int marked = 0, inverted_marked = 0;
  for (const input::Formulation formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const ElementBlock block =
        make_element_block(formulation, steel, 0.05, 100, box.count, box.connectivity.data(), box.x_ref, law);
    ASSERT_FALSE(block.failure.status.empty());
    set_material_time_step(block, 1e-7);
    block.failure.erode_step = limit;
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 12; ++trial) {
      const NodalVectors u = shaken(box, 0.1 + 0.02 * trial, rng);
      // The simple checks, element by element.
      std::vector<std::uint8_t> expected(block.count, 0);
      CurrentStep kept{std::numeric_limits<double>::infinity(), 0};
      for (std::uint32_t e = 0; e < block.count; ++e) {
        ElementVectors x;
        for (int k = 0; k < 8; ++k) {
          const std::uint32_t n = block.connectivity[8 * std::size_t(e) + std::size_t(k)];
          x.x[k] = box.x_ref.x[n] + u.x[n], x.y[k] = box.x_ref.y[n] + u.y[n],
          x.z[k] = box.x_ref.z[n] + u.z[n];
        }
        const double dt = hex8::current_characteristic_length(x) / c1;
        const bool inverted = find_inverted_element(block, e, e + 1, box.x_ref, u).found;
        ASSERT_GT(std::abs(dt - limit), 1e-12 * limit);  // no element on the edge of the rule
        expected[e] = dt < limit || inverted;
        inverted_marked += inverted && formulation == input::Formulation::hex8;
        if (!expected[e] && dt < kept.dt) kept = {dt, block.first_element + e};
      }
      for (const int t : {1, 2}) {
        set_threads(t);
        for (const bool in_pass : {false, true}) {
          block.failure.distorted.assign(block.count, 0);
          CornerChecks checks;
          if (in_pass) {
            NodalVectors f(box.x_ref.size());
            request_corner_checks(block, box.x_ref, true, true);
            add_internal_forces(block, u, f, nullptr);
            checks = corner_checks_of_pass(block);
          } else {
            checks = check_corners(block, box.x_ref, u);
          }
          EXPECT_EQ(block.failure.distorted, expected) << "trial " << trial;
          EXPECT_FALSE(checks.inverted.found);
          EXPECT_EQ(checks.step.element, kept.element);
          EXPECT_NEAR(checks.step.dt, kept.dt, 1e-13 * kept.dt);
        }
      }
      for (const std::uint8_t m : expected) marked += m;
    }
  }
  set_threads(threads);
  EXPECT_GT(marked, 50);  // both kinds seen
  EXPECT_GT(inverted_marked, 5);
}

// An element marked distorted at step n leaves with what it carried then: the pass of
// n+1 books U^n + H^n + dt/2 f^n.v^{n+1/2} from what the pass of n held (ElementFailure::
// held), against the element's own energy and forces at u^n computed on their own. At
// u^{n+1} the crushed and inverted elements' forces are no measure of it: the booking
// from them is off.
TEST(CornerChecks, AnElementMarkedDistortedLeavesWithWhatItCarried) {
  const Box box = make_box(37, 5, 6, 1.0);
  const material::MaterialLaw law = failing_law();
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref, law);
  const double dt = 1e-4;  // large: the step moves the nodes by up to 0.2
  set_material_time_step(block, dt);
  block.failure.erode_step = 0.75 / steel.dilatational_wave_speed();
  block.failure.distorted.assign(block.count, 0);
  block.failure.held.assign(block.count * ElementFailure::held_size(8),
                            std::numeric_limits<double>::quiet_NaN());
  std::mt19937_64 rng(5);
  const NodalVectors u = shaken(box, 0.3, rng), v = shaken(box, 2e3, rng);
  NodalVectors u_next(u.size());
  for (std::size_t n = 0; n < u.size(); ++n)
    u_next.x[n] = u.x[n] + dt * v.x[n], u_next.y[n] = u.y[n] + dt * v.y[n],
    u_next.z[n] = u.z[n] + dt * v.z[n];
  block.failure.velocity = &v;
  // Step n: the marks, and what the marked elements carry, each on its own.
  NodalVectors f(u.size());
  request_corner_checks(block, box.x_ref, true, true);
  add_internal_forces(block, u, f, nullptr);
  corner_checks_of_pass(block);  // the request is for one pass
  double expected = 0.0;
  int marked = 0;
  for (std::uint32_t e = 0; e < block.count; ++e) {
    if (block.failure.distorted[e] == 0) continue;
    ++marked;
    NodalVectors f_e(u.size());
    const ElementEnergies own = add_internal_forces(block, e, e + 1, u, f_e, nullptr);
    double power = 0.0;
    for (int k = 0; k < 8; ++k) {
      const std::uint32_t n = block.connectivity[8 * std::size_t(e) + std::size_t(k)];
      power += f_e.x[n] * v.x[n] + f_e.y[n] * v.y[n] + f_e.z[n] * v.z[n];
    }
    expected += own.strain + own.hourglass + 0.5 * dt * power;
  }
  ASSERT_GT(marked, 5);
  // Step n+1 starts from the states step n wrote; the damage pass failed them.
  commit_material_state(block);
  for (std::uint32_t e = 0; e < block.count; ++e)
    if (block.failure.distorted[e] != 0) block.failure.status[e] = ElementStatus::failed;
  block.failure.any_not_alive = true;
  NodalVectors f_next(u.size());
  const double booked = add_internal_forces(block, u_next, f_next, nullptr).eroded;
  EXPECT_NEAR(booked, expected, 1e-12 * std::abs(expected));
  // From the state at u^{n+1} instead (no element held):
  std::fill(block.failure.held.begin(), block.failure.held.end(), std::numeric_limits<double>::quiet_NaN());
  const double from_next = add_internal_forces(block, u_next, f_next, nullptr).eroded;
  // Measured 8.0e-3 off: the stored energy and plastic work at u^{n+1} less dt/2
  // f^{n+1}.v^{n+1/2} are the trapezoid's work of the step only where the points flow
  // (the plastic work is that trapezoid's less the stored energy's change), and an
  // inverted element's forces are no measure at all.
  EXPECT_GT(std::abs(from_next - expected), 1e-3 * std::abs(expected));
}

}  // namespace
}  // namespace exdyn::element
