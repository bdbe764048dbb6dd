// Single-surface contact through whole runs: where only two known faces ever touch it
// gives the fields of the two-pass pair between them (the two plates of the seed paper
// as one `surface: all`, the arms of a U as one surface), and faces that share nodes
// never touch (an L whose inner corner closes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "../support/deck_run.hpp"
#include "input/deck_reader.hpp"

namespace {

using exdyn::input::Deck;
using exdyn::input::Override;
using exdyn::testing::DeckRun;

// The deck with its first contact pair made `surface: all`.
Deck as_surface_all(Deck deck) {
  auto& pair = deck.contact.front();
  pair.single_surface = pair.surface_all = true;
  pair.slave = pair.master = exterior_faces(deck);
  return deck;
}

// The largest difference between two fields over the largest entry of the first.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    largest = std::max(largest, std::abs(a[i]));
    difference = std::max(difference, std::abs(a[i] - b[i]));
  }
  return largest > 0.0 ? difference / largest : difference;
}

// Every field of the last step the same bits; the penetration history and, between two
// parts, the contact force histories to 1e-12 of their largest (one pass's sums against
// two passes': the bits too, as it is). Within one part a surface's force is zero (the
// force on its first part from the others), where a pair's is the force on its slave side.
void expect_same_run(const DeckRun& pair, const DeckRun& surface, const std::string& contact,
                     bool two_parts) {
  ASSERT_EQ(pair.summary.status, "completed");
  ASSERT_EQ(surface.summary.status, "completed");
  ASSERT_EQ(pair.summary.steps, surface.summary.steps);
  for (const char* field : {"displacement", "velocity", "stress", "contact_force"})
    EXPECT_EQ(pair.final(field), surface.final(field)) << field;
  // The sums of the points' force magnitudes do not cancel within one part: the same
  // as the pair's (summed in another order) on one body too.
  for (const char* history : {"force", "normal_force", "max_penetration", "normal_force_sum"}) {
    if (!two_parts && (history == std::string("force") || history == std::string("normal_force"))) continue;
    const std::string name = "contact/" + contact + "/" + history;
    EXPECT_LE(relative_difference(pair.history(name), surface.history(name)), 1.0e-12) << name;
  }
  EXPECT_GT(pair.summary.contact.max_penetration_over_h, 0.0);  // they did touch
}

struct PlateCase {
  std::string name;
  const char* deck;
  std::vector<Override> overrides;
};

void PrintTo(const PlateCase& c, std::ostream* out) { *out << c.name; }

class TwoPlatesAsOneSurface : public ::testing::TestWithParam<PlateCase> {};

// The seed's plate impact as input/plates_one_surface.yaml gives it, `surface: all`, at
// its size: the fields of plate_impact.yaml's two-pass pair, bit for bit.
TEST(SingleSurface, ThePlatesDeckGivesThePairsFields) {
  const DeckRun pair("plate_impact.yaml");
  const DeckRun single("plates_one_surface.yaml");
  ASSERT_EQ(single.deck.contact.front().slave.size(), 6u);  // xmin, xmax, zmax of each plate
  expect_same_run(pair, single, "interface", true);
}

// The same on smaller meshes on to c1 t / d = 0.96, with nodes, quadrature points and
// mortar, hex8 and hex20 (the deck's pair made `surface: all`).
TEST_P(TwoPlatesAsOneSurface, GiveTheFieldsOfTheTwoPassPair) {
  const PlateCase& c = GetParam();
  const Deck deck = exdyn::input::read_deck(DeckRun::source_path(c.deck), c.overrides);
  const DeckRun pair(deck);
  const Deck surface = as_surface_all(deck);
  ASSERT_EQ(surface.contact.front().slave.size(), 6u);
  const DeckRun single(surface);
  expect_same_run(pair, single, "interface", true);
}

const std::vector<Override> hex8_plates{
    {"parts[0].elements", "[20, 1, 20]"}, {"parts[1].elements", "[20, 1, 20]"}, {"time.end_time", "4.0e-7"}};
const std::vector<Override> hex20_plates{
    {"parts[0].elements", "[12, 1, 12]"}, {"parts[1].elements", "[12, 1, 12]"}, {"time.end_time", "4.0e-7"}};

std::vector<Override> with(std::vector<Override> overrides, const char* points) {
  overrides.push_back({"contact[0].slave_points", points});
  return overrides;
}

std::string case_name(const ::testing::TestParamInfo<PlateCase>& param) { return param.param.name; }

INSTANTIATE_TEST_SUITE_P(
    PlateImpact, TwoPlatesAsOneSurface,
    ::testing::Values(PlateCase{"hex8_nodes", "plate_impact.yaml", hex8_plates},
                      PlateCase{"hex8_quadrature", "plate_impact.yaml", with(hex8_plates, "quadrature")},
                      PlateCase{"hex20_quadrature", "plate_impact_hex20.yaml", hex20_plates},
                      PlateCase{"hex20_nodes", "plate_impact_hex20.yaml", with(hex20_plates, "nodes")},
                      PlateCase{"hex8_mortar", "plate_impact.yaml", with(hex8_plates, "mortar")},
                      PlateCase{"hex20_mortar", "plate_impact_hex20.yaml", with(hex20_plates, "mortar")}),
    case_name);

// input/u_shape.yaml: the arms of a U bent together touch; the U's inner faces as one
// surface give the fields of a pair declared between the arms' facing faces.
TEST(SingleSurface, TheArmsOfAUTouchAsThePairBetweenThemSays) {
  const Deck deck = exdyn::input::read_deck(DeckRun::source_path("u_shape.yaml"));
  const DeckRun single(deck);
  Deck as_pair = deck;
  auto& pair = as_pair.contact.front();
  pair.single_surface = false;
  pair.slave = {deck.contact.front().slave[0]};   // u.inner_left
  pair.master = {deck.contact.front().slave[1]};  // u.inner_right
  pair.two_pass = true;
  const DeckRun paired(as_pair);
  expect_same_run(paired, single, "self", false);
  const auto& c = single.summary.contact;
  std::printf("u shape: %ld steps, max penetration / h %.4f, energy error %.2e\n", single.summary.steps,
              c.max_penetration_over_h, single.summary.energy.max_relative_error);
  EXPECT_LT(c.max_penetration_over_h, 0.03);
  EXPECT_LE(single.summary.energy.max_relative_error, 0.01);
  // Within one part the contact force on it is zero: its points' forces and their reactions.
  for (double f : single.history("contact/self/force")) EXPECT_EQ(f, 0.0);
  // What shows the contact: the sum of the points' normal force magnitudes, and the
  // points pressed at its peak, the pair's.
  const std::vector<double> sum = single.history("contact/self/normal_force_sum");
  const double peak = *std::max_element(sum.begin(), sum.end());
  const auto& mine = single.summary.contact.pairs.front();
  const auto& theirs = paired.summary.contact.pairs.front();
  std::printf("u shape: normal force sum peak %.4g N, %ld points pressed then (pair: %.4g N, %ld)\n",
              mine.peak_normal_force_sum, mine.points_in_contact_at_peak, theirs.peak_normal_force_sum,
              theirs.points_in_contact_at_peak);
  EXPECT_GT(peak, 0.0);
  EXPECT_LE(peak, mine.peak_normal_force_sum);
  EXPECT_NEAR(mine.peak_normal_force_sum, theirs.peak_normal_force_sum, 1e-12 * theirs.peak_normal_force_sum);
  EXPECT_EQ(mine.points_in_contact_at_peak, theirs.points_in_contact_at_peak);
  EXPECT_GT(mine.points_in_contact_at_peak, 0);
}

struct SlotCase {
  std::string name;
  std::vector<Override> overrides;
};

void PrintTo(const SlotCase& c, std::ostream* out) { *out << c.name; }

class ACWhoseSlotCloses : public ::testing::TestWithParam<SlotCase> {};

// input/c_slot.yaml: a C whose slot closes as its upper arm swings down, the slot's back
// one thin brick tall (0.16 of the others), the surface the Gmsh part's whole boundary.
// The boundary is one face that folds: the surface takes each side between its folds as
// a face (mesh/face_sides.hpp), so the slot's faces keep their own element length and a
// node at the arm's tip its stiffness on each side; a Gauss point's penalty is capped
// for the face it meets, not for the thin brick's light nodes elsewhere on the surface.
// The fields are the two-pass pair's between the slot's faces, bit for bit.
TEST_P(ACWhoseSlotCloses, AsOneSurfaceGivesThePairsFields) {
  const SlotCase& c = GetParam();
  const Deck surface = exdyn::input::read_deck(DeckRun::source_path("c_slot.yaml"), c.overrides);
  ASSERT_TRUE(surface.contact.front().surface_all);
  // The pair first, then the case's settings over it.
  std::vector<Override> overrides{
      {"contact", "[{name: self, slave: [c.slot_lower], master: [c.slot_upper], two_pass: true}]"}};
  overrides.insert(overrides.end(), c.overrides.begin(), c.overrides.end());
  const Deck as_pair = exdyn::input::read_deck(DeckRun::source_path("c_slot.yaml"), overrides);
  const DeckRun single(surface);
  const DeckRun paired(as_pair);
  expect_same_run(paired, single, "self", false);
  const auto& mine = single.summary.contact.pairs.front();
  const auto& theirs = paired.summary.contact.pairs.front();
  std::printf(
      "c slot %s: peak normal force sum %.6g N, %ld points (pair: %.6g N, %ld), penetration / h %.4f\n",
      c.name.c_str(), mine.peak_normal_force_sum, mine.points_in_contact_at_peak,
      theirs.peak_normal_force_sum, theirs.points_in_contact_at_peak,
      single.summary.contact.max_penetration_over_h);
  EXPECT_EQ(mine.points_in_contact_at_peak, theirs.points_in_contact_at_peak);
  EXPECT_GT(mine.points_in_contact_at_peak, 0);
}

// 20-node bricks to 24 us: 8 us after the first touch (a hex20 step is a fifth of a hex8
// one). The sanitizer build, about 10 times slower, runs them to 18 us: the same paths,
// 2 us of contact.
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* hex20_slot_end = "1.8e-5";
#else
constexpr const char* hex20_slot_end = "2.4e-5";
#endif
const std::vector<Override> hex20_slot{{"parts[0].mesh.file", "meshes/c_slot_hex20.msh"},
                                       {"parts[0].formulation", "hex20"},
                                       {"time.end_time", hex20_slot_end}};

INSTANTIATE_TEST_SUITE_P(CSlot, ACWhoseSlotCloses,
                         ::testing::Values(SlotCase{"hex8_nodes", {}},
                                           SlotCase{"hex8_quadrature",
                                                    {{"contact[0].slave_points", "quadrature"}}},
                                           SlotCase{"hex8_mortar", {{"contact[0].slave_points", "mortar"}}},
                                           SlotCase{"hex20_quadrature", hex20_slot},
                                           SlotCase{"hex20_mortar", with(hex20_slot, "mortar")}),
                         [](const ::testing::TestParamInfo<SlotCase>& param) { return param.param.name; });

// The L (the U without its right arm; input/meshes/u_shape.geo, right = 0): its arm
// pushed at the tip bends towards the base, so the inner corner closes. With every face
// of the body in one surface, no point touches anything: the corner's faces share its
// nodes, and no other faces face each other.
TEST(SingleSurface, AnLWhoseInnerCornerClosesTakesNoContact) {
  const Deck deck = exdyn::input::read_deck(DeckRun::source_path("u_shape.yaml"),
                                            {{"parts[0].mesh.file", "meshes/l_shape_hex8.msh"},
                                             {"contact[0].surface", "all"},
                                             {"rigid_walls[1].slave", "[u.tip_left]"},
                                             {"rigid_walls[1].velocity", "[0, 0, 0]"},
                                             {"rigid_walls[1].point", "[-1.0, 0, 0]"},
                                             {"rigid_walls[1].normal", "[1, 0, 0]"}});
  const DeckRun run(deck);
  ASSERT_EQ(run.summary.status, "completed");
  // The corner closed: the arm's inner face turned towards the base (its node at the
  // top of the inner face moved 1.5 mm or more in x, the corner's not).
  const auto u = run.final("displacement");
  double tip_ux = 0.0;
  for (std::size_t i = 0; i < u.size() / 3; ++i) tip_ux = std::max(tip_ux, u[3 * i]);
  EXPECT_GT(tip_ux, 1.5e-3);
  // (contact_force holds the wall's forces too: no point of the surface pressed is no
  // penetration at any step.)
  for (double depth : run.history("contact/self/max_penetration")) EXPECT_EQ(depth, 0.0);
  ASSERT_EQ(run.summary.contact.pairs.size(), 1u);
  EXPECT_EQ(run.summary.contact.pairs[0].figures.max_penetration_over_h, 0.0);
  EXPECT_GT(run.summary.contact.pairs[0].figures.projections,
            0);  // points were checked: it could have failed
}

// The foot of a Taylor rod (400 m/s on a rigid wall, the first layer of bricks 0.27 mm
// thick, graded along the rod): as the rim spreads, the side just above it turns to face
// up, towards the impact face's rim segments, with its nodes already inside the corner,
// one brick above those segments. The rule of a contact that begins deep (more than 0.1
// of the point's element length: no step's approach does that) counts its gap from its
// start: no force, no penetration guard (without it, a node is taken as 0.41 h inside the
// impact face at step 208, 3.04 us, and the run stops).
TEST(SingleSurface, TheSideAboveASpreadingRimIsNotTakenInsideTheImpactFace) {
  const Deck deck = exdyn::input::read_deck(DeckRun::source_path("taylor_wall.yaml"),
                                            {{"parts[0].grading", "[1, 1, 4]"},
                                             {"parts[0].initial_velocity", "[0, 0, -400]"},
                                             {"contact", "[{name: self, surface: all}]"},
                                             {"time.end_time", "4.0e-6"},
                                             {"output.every", "100000"}});
  const DeckRun run(deck);
  ASSERT_EQ(run.summary.status, "completed");
  EXPECT_GT(run.summary.steps, 250);  // past step 208
  ASSERT_EQ(run.summary.contact.pairs.size(), 1u);
  EXPECT_LT(run.summary.contact.pairs[0].figures.max_penetration_over_h, 0.05);
  EXPECT_GT(run.summary.contact.pairs[0].figures.projections, 0);  // points were checked
}

}  // namespace
