// One direction of a contact pair: every slave point against the master
// segments. A slave point is a slave node (slave_points: nodes) or a Gauss point of
// a slave segment (slave_points: quadrature, the pre-discretization penalty of
// Gabriel, Plesek and Ulbin 2004). A pass runs the contact pipeline of one step:
//   global search (bucket grid, only when nodes have moved enough)
//   -> local search (the deck's method) for every candidate pair
//   -> the closest inside projection of each slave point (the point's one contact);
//      with none, the closest point of a fold's edge the point lies behind (edge_contact.hpp)
//   -> penalty forces on the slave point's nodes and the segment's nodes, with Coulomb
//      friction from a stick anchor on the master surface (friction.hpp).
// A pair with `two_pass: true` runs two passes, the second with the roles swapped.
// Segments have 4 or 8 nodes (contact::SegmentNodes), and one pass may mix them.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "contact/bucket_search.hpp"
#include "contact/edge_contact.hpp"
#include "contact/friction.hpp"
#include "contact/local_search.hpp"
#include "contact/mortar.hpp"

namespace exdyn::contact {

// A Gauss point of a slave segment.
struct QuadraturePoint {
  std::uint32_t segment = 0;  // index into ContactSurfaces::slave_segments
  Xi xi{};
  double weight = 0.0;  // Gauss weight (w1 w2) times the reference area element |a1 x a2|, m^2
};

// A segment at a slave node of a single surface: the segment, the node's place among
// its nodes, and which of the node's sides (the faces it lies on) the segment is of.
struct NodeCorner {
  std::uint32_t segment = 0;
  std::uint8_t corner = 0, side = 0;
};
inline constexpr std::size_t max_node_sides = 8;

// The geometry of a pass, fixed for the run (global node ids).
struct ContactSurfaces {
  bool quadrature = false;  // the slave points: Gauss points (true) or nodes
  // Mortar (mortar_pass.hpp): the slave points are made each step, the points of the
  // pieces where the slave segments overlap the master segments; `quadrature` is false.
  bool mortar = false;
  std::vector<std::uint32_t> slave_nodes;          // every node of the slave faces, unique, sorted
  std::vector<SegmentNodes> slave_segments;        // the slave faces' segments (quadrature only)
  std::vector<QuadraturePoint> quadrature_points;  // quadrature only: the slave points
  // Penalty stiffness of each slave point, N/m: nodes, scale kappa M A / L before the
  // frequency caps (automatic rule) or the deck's fixed stiffness; quadrature points,
  // the pressure per length kappa (capped, docs/contact.md) times the point's weight.
  std::vector<double> stiffness;
  std::vector<double> normal_length;   // element length normal to the slave face at each point, m
  std::vector<SegmentNodes> segments;  // master segments, outward oriented
  // Per master segment, what the surface does past its edges (edge_contact.hpp): goes
  // on (shared with another master segment, or on a symmetry plane); empty: nothing
  // past any edge (no contact at folds).
  std::vector<SegmentEdges> edges;
  std::vector<std::uint32_t> moving_nodes;  // slave and master nodes (for the rebuild test), unique

  // Mortar: per slave segment its pressure per length kappa (Pa/m, capped as the
  // quadrature points' are), its element length normal to the face (m) and the mean
  // tributary area per mass of its nodes (m^2/kg); per master segment the same mean
  // (the penalty of docs/contact.md, "Mortar"); the points of the rule on each triangle.
  std::vector<double> segment_kappa, segment_length, slave_area_per_mass, master_area_per_mass;
  int triangle_points = 3;

  // The points of a mortar piece (a pass over this step's mortar points, mortar_pass.hpp):
  // each point's one candidate is the master segment of its piece, and a converged
  // minimum counts there even a little outside it (|xi_a| <= 1 + own_segment_reach),
  // where the pieces' straight edges cut a curved master's; its dashpot acts on the
  // reduced mass point_mass[p] (kg).
  bool own_segment = false;
  std::vector<double> point_mass;

  // Single-surface contact (single_surface.hpp): the slave points are the surface's and
  // `segments` the same surface's (a Gauss point's slave segment k is master segment k).
  // A slave node's corners (each segment at the node, the node's place in it and the
  // side, i.e. the face, it belongs to among the node's) and its sides' stiffness, N/m.
  // first_part_*: whether a point (mortar: a slave segment) or a segment lies on the part
  // of the surface's first face: the pass's force is the force on that part (the
  // others' points add their reactions on its segments).
  bool single_surface = false;
  std::vector<std::uint32_t> corner_begin;  // node p's corners: [corner_begin[p], corner_begin[p + 1])
  std::vector<NodeCorner> node_corners;
  std::vector<std::uint32_t> side_begin;  // node p's sides: [side_begin[p], side_begin[p + 1])
  std::vector<double> side_stiffness;
  std::vector<std::uint8_t> first_part_point, first_part_segment;
  // Per master segment, the segment across each edge (the order of SegmentEdges): -1
  // none (on a rank: or not in its view), -2 more than one.
  std::vector<std::array<std::int32_t, 4>> edge_neighbours;
  // Quadrature points with the automatic penalty: each master segment's face (among
  // the surface's faces, in order) and, per slave segment and face, the pressure per
  // length kappa (Pa/m) capped for the largest 1/m of that face's nodes, as a pair whose
  // master side is that face caps it. A point's stiffness is its slave segment's kappa
  // for the face of the segment it meets, times its weight. Empty: `stiffness`.
  std::vector<std::uint32_t> segment_face;
  std::size_t face_count = 0;
  std::vector<double> face_kappa;  // slave segment s, face f: [s * face_count + f]

  // Erosion (docs/contact.md, "Faces that erosion opens"), a single surface over parts
  // that can fail: per master segment the element it bounds and the element across it
  // (no_element: none, or on a part that cannot fail); whether each segment and each
  // slave point is on the body's boundary now: a segment while its element lives and
  // the one across does not, a point while it lies on such a segment. The model sets
  // them as elements erode (model/opened_faces.hpp); empty: every one, always.
  std::vector<std::uint32_t> segment_element, segment_across;
  std::vector<std::uint8_t> segment_live, point_live;
  // And each segment's four edges numbered, a number per edge of the surface (the
  // segments sharing an edge share it), in the order of edge_corners: what the edges
  // and edge neighbours are counted over as the segments change.
  std::vector<std::uint32_t> edge_ids;

  std::size_t point_count() const { return quadrature ? quadrature_points.size() : slave_nodes.size(); }
  bool segment_on(std::size_t s) const { return segment_live.empty() || segment_live[s] != 0; }
  bool point_on(std::size_t p) const { return point_live.empty() || point_live[p] != 0; }
};

inline constexpr std::uint32_t no_element = 0xffffffffu;

inline constexpr double own_segment_reach = 0.25;

// A contact on a single surface that begins deeper than this fraction of the element
// length began inside (contact_pass.cpp, apply_exposure_offsets).
inline constexpr double begun_inside = 0.1;

struct ContactPassSettings {
  ProjectFn project = nullptr;  // chosen once from the deck's method
  // The method that settles a projection `project` failed on (project_settled); null:
  // none, the failure gives no contact (the method studies).
  ProjectFn fallback = nullptr;
  ProjectionSettings projection;
  InitialGuess initial_guess = InitialGuess::lsp;
  double damping_ratio = 0.0;  // zeta, fraction of critical
  // Automatic stiffness of slave nodes: at each contact k = scale min(kappa M A / L,
  // the frequency caps of penalty.hpp for the actual 1/m_s + sum N_i^2 / m_i).
  // (Quadrature points carry their capped stiffness in ContactSurfaces::stiffness.)
  bool automatic_stiffness = true;
  double stiffness_scale = 1.0;
  double dt = 0.0;  // the step the caps are taken at, s
  // When the step follows the deformation, the automatic stiffness follows the step:
  // dt = dt_0 r and stiffness_growth = 1 / r^2 with r = dt^{n-1/2} / dt^{1/2} the step's
  // fall since the first and dt_0 the step the stiffness was set for; else dt = dt_0 and
  // exactly 1. The caps scale so by themselves (m / dt^2); the element term
  // kappa M A / L = 2 kappa m c^2 / L^2 of a node of mass m = rho A L / 2 grows as 1 / L^2,
  // and a crushed mesh's step falls with its L.
  double stiffness_growth = 1.0;
  double set_for_dt = 0.0;       // dt_0, s
  double courant = 0.0;          // dt / the mesh's critical step
  int pass_count = 1;            // two passes put two springs on a node pair: each carries 1 / pass_count
  double search_distance = 0.0;  // largest gap that is searched for, m
  double margin = 0.0;           // extra capture: rebuild once a node has moved margin / 2, m
  double cell_size = 0.0;        // bucket cell edge, m (<= 0: automatic)
  FrictionLaw friction;          // not enabled: frictionless
};

// What a mortar pass keeps (mortar_pass.hpp): the (slave segment, master segment) pairs
// of its global search and this step's points, run as the quadrature points of a view.
// Slave segments cut together by one thread (mortar_pass.hpp).
inline constexpr std::size_t mortar_chunk = 64;

struct MortarState {
  std::vector<CandidatePair> pairs;     // point: the slave segment; sorted by slave segment, then master
  std::vector<std::size_t> pair_begin;  // slave segment s's pairs: [pair_begin[s], pair_begin[s + 1])
  NodalVectors centres;                 // each slave segment's y(0, 0) at the search, m
  std::vector<Box> slave_boxes, master_boxes;  // at the search (scratch)
  // This step's points of each chunk of mortar_chunk slave segments, with their piece.
  struct Piece {
    MortarPoint point;
    std::uint32_t master = 0, index = 0;  // the master segment, the point's place among the pair's
  };
  std::vector<std::vector<Piece>> chunk_points;
  std::vector<std::size_t> point_begin;  // slave segment s's points: [point_begin[s], point_begin[s + 1])
  ContactSurfaces view;                  // this step's points, as Gauss points of the slave segments
  // Each point's piece (slave segment, master segment, its place among the pair's
  // points): a point of the same piece at the next step takes its friction anchor.
  struct Identity {
    std::uint32_t slave = 0, master = 0, index = 0;
    auto operator<=>(const Identity&) const = default;
  };
  std::vector<Identity> identity, previous_identity;
  std::vector<Anchor> previous_anchors;
  std::vector<std::uint64_t> point_keys;  // records (many processes): each point's key
};

// The chunked scatter's scratch (force_scatter.hpp): the slots (places among the
// pass's moving nodes) of the slave nodes (or of each slave segment's nodes) and of each
// master segment's nodes, made after the candidate search numbered `rebuilds`; each
// slot's first chunk in the last call (under the call's stamp); and each chunk's points
// with writes left for the ordered phase.
struct ScatterScratch {
  std::vector<std::uint32_t> slave_slots, segment_slots;
  long rebuilds = -1;
  std::vector<std::uint64_t> first_chunk;
  std::uint32_t stamp = 0;
  std::vector<std::vector<std::uint32_t>> late;
};

struct ContactPassState {
  bool built = false;
  long rebuilds = 0;
  std::vector<CandidatePair> candidates;  // sorted by slave point, then segment
  std::vector<std::size_t> point_begin;   // slave point p's candidates: [point_begin[p], point_begin[p + 1])
  std::vector<Xi> previous_xi;            // last step's point of each candidate pair
  NodalVectors moving_at_build;           // positions of moving_nodes at the last build
  // scratch, kept to avoid allocation
  NodalVectors slave_points;  // current position of each slave point, m
  std::vector<Box> boxes;
  BucketWorkspace workspace;
  std::vector<CandidatePair> new_candidates;
  std::vector<Xi> new_previous_xi;
  std::vector<ProjectionResult> results;   // the projection of each candidate pair, this step
  std::vector<EdgeContact> edge_contacts;  // scratch: a fold's edge point of each candidate pair
  std::vector<double> force_magnitude;     // F of each slave point's contact, N (0: none)
  std::vector<Vec3> point_force;           // F n + F_t of each slave point pressed, N (0: none)
  ScatterScratch scatter;
  std::vector<double> pair_stiffness;  // k of each slave point's pair before the pass split, N/m
  std::vector<Vec3> tangential_force;  // F_t of each slave point, N (friction)
  std::vector<double> dissipation;     // the friction work of each slave point this step, J
  std::vector<Anchor> anchors;         // friction: each slave point's stick anchor, kept from step to step
  // This step: the total contact force on the pass's slave side (N), its normal and
  // tangential parts, and its deepest penetration (m, >= 0): the pair's histories.
  Vec3 slave_force{};
  Vec3 slave_normal_force{};
  Vec3 slave_tangential_force{};
  double max_penetration = 0.0;
  // The sums of the magnitudes of the points' normal and tangential forces (N) and the
  // number of points pressed: on a single surface, where the vector sums cancel, what
  // shows the contact.
  double normal_force_sum = 0.0;
  double tangential_force_sum = 0.0;
  long points_in_contact = 0;
  long slipping = 0;            // slave points in contact that slip this step
  long sticking = 0;            // and those that stick
  double friction_work = 0.0;   // dissipated by friction since the start, J
  struct Contact {              // the chosen projection of each slave point
    std::int64_t segment = -1;  // -1: none
    Xi xi{};
    double gap = 0.0;
    Vec3 normal{};
  };
  std::vector<Contact> contacts;
  std::vector<std::uint8_t> admitted;  // single surface: whether each candidate pair may touch
  // A single surface: each point's contact segment of the last step (-1: none) and its
  // offset (m, <= 0): the penetration its contact began with when it began inside
  // (contact_pass.cpp, apply_exposure_offsets), which its gap is counted from.
  std::vector<std::int64_t> last_segment;
  std::vector<double> exposure_offset;
  MortarState mortar;  // a mortar pass's (ContactSurfaces::mortar)
};

struct ContactStatistics {
  long projections = 0;
  long iterations = 0;  // sum over projections
  long max_iterations = 0;
  long not_converged = 0;  // stopping test not met (no force from them)
  long saddle_points = 0;  // converged to a saddle or a maximum (no force from them)
  long fallbacks = 0;      // projections the method failed on, settled again by the fallback
                           // (counted above only when that failed too)
  double max_penetration_over_h = 0.0;
  std::uint32_t deepest_node = 0;   // the slave node of that largest penetration (for a
                                    // quadrature point, the first node of its segment)
  double max_pair_stiffness = 0.0;  // largest k of a node pair used (all passes), N/m
};

struct ContactPhaseSeconds {
  double segmentation = 0.0;  // mortar: cutting the slave segments into pieces
  double global_search = 0.0;
  double local_search = 0.0;
  double forces = 0.0;
};

// Many processes (docs/parallel.md, "Contact across ranks"): a pass's forces and gaps
// as records instead of additions, so that the owner of each node adds them in the
// order of one process. key = pass << 48 | point << 8 | slot orders them as one process
// adds them: pass after pass, slave point after slave point (`point`: the point's
// index in the whole surface), the slave side's nodes (slot i) before the master
// segment's (slot 8 + i).
struct ForceRecord {
  std::uint64_t key = 0;
  std::uint32_t node = 0;  // the pass's node id (the caller renumbers)
  std::uint32_t kind = 0;  // force: value is added; gap: value[0] is a gap, kept if smaller
  double value[3] = {0.0, 0.0, 0.0};
  static constexpr std::uint32_t force = 0, gap = 1;
};

struct RecordSink {
  std::uint64_t pass = 0;
  const std::vector<std::uint64_t>* point_keys = nullptr;  // each slave point's index in the whole surface
  std::vector<ForceRecord> records;

  std::uint64_t key(std::size_t p, int slot) const {
    return pass << 48 | std::uint64_t((*point_keys)[p]) << 8 | std::uint64_t(slot);
  }
  void add(std::size_t p, int slot, std::uint32_t node, double x, double y, double z) {
    records.push_back({key(p, slot), node, ForceRecord::force, {x, y, z}});
  }
  void gap(std::size_t p, int slot, std::uint32_t node, double g) {
    records.push_back({key(p, slot), node, ForceRecord::gap, {g, 0.0, 0.0}});
  }
};

// Whether a projection failed: its stopping test not met, or it stopped on a saddle or
// a maximum of the distance. It gives no contact as it is.
inline bool projection_failed(const ProjectionResult& r) {
  return !r.converged || r.stationary == StationaryKind::saddle || r.stationary == StationaryKind::maximum;
}

// The point's projection onto the segment by the pass's method from `start`; where that
// failed, by the fallback method from the same start (`settled` true then).
inline ProjectionResult project_settled(const ContactPassSettings& settings, const Segment& segment,
                                        Vec3 point, Xi start, bool& settled) {
  ProjectionResult r = settings.project(segment, point, start, settings.projection);
  settled = settings.fallback != nullptr && projection_failed(r);
  if (settled) r = settings.fallback(segment, point, start, settings.projection);
  return r;
}

// The largest distance (m) a node of the pass has moved since its last candidate
// search (infinite before the first): the search is redone beyond margin / 2.
double largest_motion_since_build(const ContactSurfaces& surfaces, const ContactPassState& state,
                                  const NodalVectors& x_ref, const NodalVectors& u);

// Runs one pass at the current configuration x = x_ref + u with the velocities v
// (m/s, the latest half-step velocities). Adds the contact forces to `force` (N),
// writes the gap of each slave node to gap[node] where it is smaller than what is
// there (callers start from +infinity and zero what stays so); with quadrature
// points, a node's gap is the smallest of the points of the segments it belongs to.
// With `records`, the forces and gaps go there instead of to `force` and `gap`.
// search_when_moved: the pass searches again once a node has moved margin / 2 since
// its last search; false where the caller decides that (the distributed contact, from
// the motion over all ranks): the pass then searches only when it has no candidates
// yet or the caller has reset them (state.built false).
void run_contact_pass(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                      ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u,
                      const NodalVectors& v, const std::vector<double>& mass, NodalVectors& force,
                      std::vector<double>& gap, ContactStatistics& statistics, ContactPhaseSeconds& seconds,
                      RecordSink* records = nullptr, bool search_when_moved = true);

}  // namespace exdyn::contact
