// Contact on the faces that erosion opens (docs/contact.md, "Faces that erosion opens"):
// a punch driven down a column of bricks that fail one after another
// (input/eroding_column.yaml), checked against the geometry at every step, and a rod
// punching a plug out of a plate (input/punch_through.yaml).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "../support/deck_run.hpp"
#include "input/deck_reader.hpp"
#include "model/contact_geometry.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "model/opened_faces.hpp"
#include "model/single_surface_setup.hpp"

namespace {

using exdyn::testing::DeckRun;
using exdyn::testing::read_dataset;

constexpr double brick = 1.0e-3;  // the column's bricks: 1 mm cubes

class ErodingColumn : public ::testing::TestWithParam<std::string> {};

INSTANTIATE_TEST_SUITE_P(Bricks, ErodingColumn, ::testing::Values("hex8", "hex8r", "hex20"));

TEST_P(ErodingColumn, ThePunchStopsAtEachFaceErosionOpens) {
  const std::string formulation = GetParam();
  const bool quadratic = formulation == "hex20";
  // hex20 takes 3,900 steps: every 10th is enough to follow it.
  const DeckRun run("eroding_column.yaml",
                    {exdyn::input::parse_override("parts[1].formulation=" + formulation),
                     exdyn::input::parse_override("parts[0].formulation=" + formulation),
                     exdyn::input::parse_override(std::string("output.every=") + (quadratic ? "10" : "1"))});
  ASSERT_EQ(run.summary.status, "completed");
  EXPECT_EQ(run.summary.energy.eroded_elements, 4);
  // Small strain: the balance with the eroded energy, the contact's and the punch's
  // work closes to round-off (measured 1.8e-14 hex8, 3.8e-14 hex8r; hex20 5.0e-11, its
  // curved segments' slave points).
  EXPECT_LT(run.summary.energy.max_relative_error, quadratic ? 1e-9 : 1e-12) << formulation;
  const std::vector<double> x_ref = read_dataset(run.h5(), "/mesh/coordinates").values;
  const std::vector<double> connectivity = read_dataset(run.h5(), "/mesh/connectivity").values;
  const std::size_t per_element = quadratic ? 20 : 8;
  const std::vector<double> force = run.history("contact/all/force");
  const std::vector<double> penetration = run.history("contact/all/max_penetration");
  // Element 0 is the punch, 1 (bottom) to 4 (top) the column; VTK order: corners 4-7 on top.
  auto node = [&](std::size_t e, std::size_t k) { return std::size_t(connectivity[per_element * e + k]); };
  const long every = quadratic ? 10 : 1;
  double worst = -1.0;
  long pressed_after_first_erosion = 0;
  for (long n = 0; n <= run.summary.steps; n += every) {
    const std::vector<double> u = run.at(n, "displacement");
    const std::vector<double> status = run.at(n, "status");
    auto z = [&](std::size_t i) { return x_ref[3 * i + 2] + u[3 * i + 2]; };
    std::size_t top = 0;  // the highest brick left
    for (std::size_t e = 1; e <= 4; ++e)
      if (status[e] != 0.0) top = e;
    if (top == 0) break;
    double punch_lowest = INFINITY, face_highest = -INFINITY;
    for (std::size_t k = 0; k < 4; ++k) punch_lowest = std::min(punch_lowest, z(node(0, k)));
    for (std::size_t k = 4; k < 8; ++k) face_highest = std::max(face_highest, z(node(top, k)));
    const double overlap = face_highest - punch_lowest;
    worst = std::max(worst, overlap);
    // The contact reports it. Its slave nodes (hex8): the deepest node along the face's
    // normal, where the highest face node and the lowest punch node are not one node's
    // (the faces tilt a little), within a factor of 2 of this bound. Its Gauss points
    // (hex20): inside the faces, where the corners' overlap is not theirs; some.
    if (overlap > 2.0e-3 * brick) {
      EXPECT_GT(penetration[std::size_t(n)], quadratic ? 0.0 : 0.5 * overlap) << "step " << n;
    }
    if (status[4] == 0.0 && force[3 * std::size_t(n) + 2] != 0.0) ++pressed_after_first_erosion;
  }
  EXPECT_LT(worst, 0.02 * brick);
  EXPECT_GT(worst, 0.0);  // the punch does press the faces
  EXPECT_GT(pressed_after_first_erosion, 0);
}

TEST(PunchThrough, TheRodLeavesThroughThePlugItCutsNeverInsideAnExposedFace) {
  const DeckRun run("punch_through.yaml");
  ASSERT_EQ(run.summary.status, "completed");
  EXPECT_GT(run.summary.energy.eroded_elements, 500);
  EXPECT_LT(run.summary.contact.pairs.at(0).figures.max_penetration_over_h, 0.15);
  // Finite strain: second order in the step (measured 2.8e-6; docs/theory.md, "Energy").
  EXPECT_LT(run.summary.energy.max_relative_error, 1.0e-5);
  // The rod's nodes (those of the first part's elements): its mean velocity, and its
  // nose below the plate.
  const std::vector<double> x_ref = read_dataset(run.h5(), "/mesh/coordinates").values;
  const std::vector<double> part = read_dataset(run.h5(), "/mesh/part").values;
  const std::vector<double> connectivity = read_dataset(run.h5(), "/mesh/connectivity").values;
  std::vector<std::size_t> rod;
  for (std::size_t e = 0; e < part.size(); ++e) {
    if (part[e] != 0.0) continue;
    for (std::size_t k = 0; k < 8; ++k) rod.push_back(std::size_t(connectivity[8 * e + k]));
  }
  std::sort(rod.begin(), rod.end());
  rod.erase(std::unique(rod.begin(), rod.end()), rod.end());
  const std::vector<double> u = run.final("displacement"), v = run.final("velocity");
  double speed = 0.0, nose = INFINITY;
  for (const std::size_t i : rod) {
    speed += v[3 * i + 2];
    nose = std::min(nose, x_ref[3 * i + 2] + u[3 * i + 2]);
  }
  speed /= double(rod.size());
  EXPECT_GT(-speed, 240.0);
  EXPECT_LT(-speed, 260.0);
  EXPECT_LT(nose, -1.0e-3);  // through the plate's back face
}

}  // namespace

// follow_life counts the edges and edge neighbours by edge number (the fast path);
// segment_edges and edge_neighbours count them by a map of node pairs (the simple one).
// With a scatter of the plate's bricks gone, the two agree on every segment.
TEST(OpenedFaces, FollowLifeGivesTheEdgesAndNeighboursOfTheSimpleCount) {
  const exdyn::input::Deck deck =
      exdyn::input::read_deck(std::string(EXDYN_SOURCE_DIR) + "/input/punch_through.yaml",
                              {exdyn::input::parse_override("parts[1].elements=[8, 8, 4]")});
  const exdyn::solver::Model model = exdyn::solver::build_model(deck);
  const double critical_dt = exdyn::solver::critical_time_step(model);
  exdyn::solver::ContactModel contact = exdyn::solver::build_contact(
      deck, model, exdyn::solver::time_stepping(deck.time, critical_dt).dt, critical_dt);
  exdyn::contact::ContactSurfaces& s = contact.pairs.at(0).passes.at(0);
  ASSERT_FALSE(s.segment_element.empty());
  std::vector<std::uint8_t> alive(model.mesh.element_count(), 1);
  const std::size_t plate = model.blocks.at(1).first_element;
  for (std::size_t e = plate; e < alive.size(); e += 3) alive[e] = 0;  // every third plate brick
  for (std::size_t e = plate; e < plate + 64; ++e) alive[e] = 0;       // and the top layer's first rows
  ASSERT_TRUE(exdyn::solver::follow_life(alive, s));
  long live = 0;
  for (const std::uint8_t on : s.segment_live) live += on;
  EXPECT_GT(live, 0);
  EXPECT_LT(live, long(s.segments.size()));
  const std::vector<exdyn::contact::SegmentEdges> edges =
      exdyn::solver::segment_edges(model, s.segments, s.segment_live);
  const std::vector<std::array<std::int32_t, 4>> neighbours =
      exdyn::solver::edge_neighbours(s.segments, s.segment_live);
  ASSERT_EQ(s.edges.size(), edges.size());
  long across = 0;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    EXPECT_EQ(s.edges[k].continued, edges[k].continued) << "segment " << k;
    EXPECT_EQ(s.edges[k].mirror_axis, edges[k].mirror_axis) << "segment " << k;
    EXPECT_EQ(s.edge_neighbours[k], neighbours[k]) << "segment " << k;
    for (const std::int32_t n : neighbours[k]) across += n >= 0;
  }
  EXPECT_GT(across, 0);
}
