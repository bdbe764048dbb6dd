#include "contact/contact_choice.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "contact/edge_contact.hpp"
#include "contact/single_surface.hpp"
#include "contact/slave_points.hpp"

namespace exdyn::contact {

namespace {

// What the edges of slave point p's candidates say (edge_contact.hpp): its closest
// boundary point (ties to the first), if nearer than `limit` and the surface goes on past
// it, decides. Behind it, along the mean normal of the segments that meet there, the
// point is in contact there (`contact` filled); in front of it, it is outside the
// master body, whatever a face further away says.
enum class FoldContact { none, contact, in_front };

// Segments meet at a point when their points lie within this fraction of the point's
// element length of each other.
constexpr double same_point = 1.0e-9;

// Room for the segments that meet at one point (a node of a brick mesh has at most 8
// faces of one surface around it; more are left out of the mean).
constexpr std::size_t max_meeting = 16;

Vec3 slave_point(const ContactPassState& state, std::size_t p) {
  return {state.slave_points.x[p], state.slave_points.y[p], state.slave_points.z[p]};
}

// What the surface does past a segment's edges, for slave point p. On a single surface
// it goes on past an edge only to a segment that p may touch there (a candidate it
// faces), or across a symmetry plane: past a convex edge whose other face turns away
// from the point (a rod's side beside its end), the point is beside the surface.
SegmentEdges edges_for_point(const ContactSurfaces& surfaces, const ContactPassState& state, std::size_t p,
                             std::uint32_t segment) {
  SegmentEdges edges = surfaces.edges[segment];
  if (!surfaces.single_surface) return edges;
  const auto first = state.candidates.begin() + std::ptrdiff_t(state.point_begin[p]);
  const auto last = state.candidates.begin() + std::ptrdiff_t(state.point_begin[p + 1]);
  for (std::size_t e = 0; e < 4; ++e) {
    const std::int32_t next = surfaces.edge_neighbours[segment][e];
    if (edges.mirror_axis[e] >= 0 || next == -2) continue;  // a mirror, or several segments: goes on
    const auto found =
        next < 0
            ? last
            : std::lower_bound(first, last, std::uint32_t(next),
                               [](const CandidatePair& pair, std::uint32_t s) { return pair.segment < s; });
    if (found == last || found->segment != std::uint32_t(next) ||
        state.admitted[std::size_t(found - state.candidates.begin())] == 0)
      edges.continued &= static_cast<std::uint8_t>(~(1u << e));
  }
  return edges;
}

FoldContact fold_contact(const ContactSurfaces& surfaces, ContactPassState& state, const NodalVectors& x_ref,
                         const NodalVectors& u, std::size_t p, double limit,
                         ContactPassState::Contact& contact) {
  if (surfaces.edges.empty()) return FoldContact::none;
  const Vec3 point = slave_point(state, p);
  EdgeContact closest;
  std::size_t closest_candidate = 0;
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c) {
    state.edge_contacts[c] = EdgeContact{};
    if (!admitted(surfaces, state, c)) continue;
    const std::uint32_t segment = state.candidates[c].segment;
    const EdgeContact edge = edge_contact(current_segment(surfaces.segments[segment], x_ref, u), point,
                                          state.results[c], edges_for_point(surfaces, state, p, segment));
    state.edge_contacts[c] = edge;
    if (edge.found && (!closest.found || edge.distance < closest.distance))
      closest = edge, closest_candidate = c;
  }
  if (!closest.found || !closest.continued || !(closest.distance < limit)) return FoldContact::none;
  const double meet = same_point * surfaces.normal_length[p];
  std::array<Vec3, max_meeting> normals{};
  std::size_t count = 0;
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1] && count < max_meeting; ++c)
    if (state.edge_contacts[c].found && norm(state.edge_contacts[c].y - closest.y) <= meet)
      normals[count++] = state.edge_contacts[c].normal;
  const Vec3 normal = mean_direction(normals.data(), count);
  if (!(norm(normal) > 0.0)) return FoldContact::none;  // a sheet folded flat on itself: no side is behind
  const double depth = dot(point - closest.y, normal);  // the gap, m
  if (!(depth < 0.0)) return FoldContact::in_front;
  contact.segment = state.candidates[closest_candidate].segment;
  contact.xi = closest.xi;
  contact.gap = depth;
  contact.normal = normal;
  return FoldContact::contact;
}

// Whether a projection is a point the segment holds: a converged minimum, or the
// robust method's closest point on the segment's boundary.
bool on_segment(const ProjectionResult& r) {
  return r.converged && (r.stationary == StationaryKind::minimum || r.on_boundary);
}

// The edge or corner that projection r lies at, when it lies within `band` (m) of an edge
// of its segment, inside or outside: the closest point of that edge (or the corner) as
// edge_contact finds it, its normal with the mirror images counted at a symmetry plane;
// not found when r lies away from every edge.
EdgeContact at_edge(const Segment& segment, Vec3 point, const ProjectionResult& r, const SegmentEdges& edges,
                    double band) {
  if (!std::isfinite(r.xi[0]) || !std::isfinite(r.xi[1])) return {};
  const SurfacePoint at =
      evaluate(segment, Xi{std::clamp(r.xi[0], -1.0, 1.0), std::clamp(r.xi[1], -1.0, 1.0)});
  ProjectionResult on_edge = r;
  bool near = false;
  for (std::size_t a = 0; a < 2; ++a) {
    const double tangent = norm(a == 0 ? at.a1 : at.a2);     // m per unit of xi_a
    const double off = (std::abs(r.xi[a]) - 1.0) * tangent;  // m beyond the edge (< 0: inside)
    if (off > band) return {};                               // too far outside
    if (off >= -band) on_edge.xi[a] = std::copysign(1.0, r.xi[a]), near = true;
  }
  if (!near) return {};
  on_edge.stationary = StationaryKind::minimum;  // (edge_contact's test of a projection that holds)
  return edge_contact(segment, point, on_edge, edges);
}

// A point whose closest inside projection `best` lies at an edge or corner that other
// candidates' projections land at too (every slave node of two faces whose nodes stand
// opposite each other) is in contact at that point along the mean normal of those
// segments: the same contact whichever of them the tie of distances goes to, and the
// same seen from either side of a mirror. Leaves `contact` as it is otherwise.
void settle_shared_point(const ContactSurfaces& surfaces, const ContactPassState& state,
                         const NodalVectors& x_ref, const NodalVectors& u, std::size_t p, std::size_t best,
                         double best_distance, ContactPassState::Contact& contact) {
  const double band = shared_point_band * best_distance + same_point * surfaces.normal_length[p];
  // Which other candidates may meet it there (the cheap tests first: most points have none).
  auto may_meet = [&](std::size_t c) {
    const ProjectionResult& r = state.results[c];
    return c != best && admitted(surfaces, state, c) && on_segment(r) &&
           r.distance <= best_distance + 2.0 * band;
  };
  bool any = false;
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1] && !any; ++c) any = may_meet(c);
  if (!any) return;
  const Vec3 point = slave_point(state, p);
  auto edge_point = [&](std::size_t c) {
    const std::uint32_t segment = state.candidates[c].segment;
    return at_edge(current_segment(surfaces.segments[segment], x_ref, u), point, state.results[c],
                   surfaces.edges.empty() ? SegmentEdges{} : edges_for_point(surfaces, state, p, segment),
                   band);
  };
  const EdgeContact first = edge_point(best);
  if (!first.found) return;
  std::array<Vec3, max_meeting> normals{first.normal};
  std::size_t count = 1;
  const double meet = same_point * surfaces.normal_length[p];
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1] && count < max_meeting; ++c) {
    if (!may_meet(c)) continue;
    const EdgeContact other = edge_point(c);
    if (other.found && norm(other.y - first.y) <= meet) normals[count++] = other.normal;
  }
  if (count < 2) return;
  const Vec3 normal = mean_direction(normals.data(), count);
  if (!(norm(normal) > 0.0)) return;
  contact.xi = first.xi;
  contact.normal = normal;
  contact.gap = dot(point - first.y, normal);
}

}  // namespace

Vec3 mean_direction(const Vec3* vectors, std::size_t count) {
  Vec3 sum{};
  std::array<double, max_meeting> values{};
  count = std::min(count, max_meeting);
  for (double Vec3::*component : {&Vec3::x, &Vec3::y, &Vec3::z}) {
    for (std::size_t i = 0; i < count; ++i) values[i] = vectors[i].*component;
    std::sort(values.begin(), values.begin() + std::ptrdiff_t(count), [](double a, double b) {
      return std::abs(a) < std::abs(b) || (std::abs(a) == std::abs(b) && a < b);
    });
    double total = 0.0;
    for (std::size_t i = 0; i < count; ++i) total += values[i];
    sum.*component = total;
  }
  const double length = norm(sum);
  return length > 0.0 ? (1.0 / length) * sum : Vec3{};
}

void admit_candidates(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                      ContactPassState& state, std::size_t p, const NodalVectors& x_ref,
                      const NodalVectors& u) {
  if (state.point_begin[p] == state.point_begin[p + 1]) return;
  const Vec3 n = point_normal(surfaces, p, x_ref, u);
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c) {
    const ProjectionResult& r = state.results[c];
    auto kept = [](double xi) { return std::isfinite(xi) ? std::clamp(xi, -1.0, 1.0) : 0.0; };
    const Vec3 m = outward_normal(current_segment(surfaces.segments[state.candidates[c].segment], x_ref, u),
                                  Xi{kept(r.xi[0]), kept(r.xi[1])});
    state.admitted[c] = dot(n, m) < -facing_cosine && !(r.gap < -settings.search_distance);
  }
}

bool counts_inside(const ContactSurfaces& surfaces, const ProjectionResult& r) {
  if (!r.converged || r.stationary != StationaryKind::minimum) return false;
  return r.inside || (surfaces.own_segment && std::abs(r.xi[0]) <= 1.0 + own_segment_reach &&
                      std::abs(r.xi[1]) <= 1.0 + own_segment_reach);
}

void choose_contact(const ContactSurfaces& surfaces, ContactPassState& state, std::size_t p,
                    const NodalVectors& x_ref, const NodalVectors& u) {
  ContactPassState::Contact& contact = state.contacts[p];
  contact = ContactPassState::Contact{};
  // The closest inside projection; ties (a point on an edge or a corner shared by
  // segments) go to the first, and settle_shared_point makes the contact the same for all.
  double best_distance = std::numeric_limits<double>::infinity();
  std::size_t best = state.candidates.size();  // none
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1]; ++c) {
    const ProjectionResult& r = state.results[c];
    if (admitted(surfaces, state, c) && counts_inside(surfaces, r) && r.distance < best_distance)
      best_distance = r.distance, best = c;
  }
  // A candidate whose plane is nearer than the best inside projection, its projection
  // outside: the point may lie in the dead zone of a fold (no inside projection at
  // all); or on a face's boundary, or in the dead zone of a shallow valley between
  // two segments, while a face further away still takes it inside (a point under a
  // rod's end face, beside its side). The nearer edge point decides then (a plane's
  // distance is a lower bound of its segment's, so no other candidate is nearer).
  // (Nearer by more than round-off: a point on an edge or corner between coplanar
  // segments is as near to their planes as to the one that takes it inside.)
  const bool none_inside = best == state.candidates.size();
  const double nearer = best_distance - same_point * surfaces.normal_length[p];
  bool nearer_outside = none_inside;
  for (std::size_t c = state.point_begin[p]; c < state.point_begin[p + 1] && !nearer_outside; ++c) {
    const ProjectionResult& r = state.results[c];
    nearer_outside = admitted(surfaces, state, c) && r.converged && !r.inside && r.distance < nearer;
  }
  if (nearer_outside && fold_contact(surfaces, state, x_ref, u, p, nearer, contact) != FoldContact::none)
    return;  // in contact at the edge, or in front of it
  if (none_inside) return;
  const std::uint32_t segment = state.candidates[best].segment;
  contact.segment = segment;
  contact.xi = state.results[best].xi;
  contact.gap = state.results[best].gap;
  contact.normal = outward_normal(current_segment(surfaces.segments[segment], x_ref, u), contact.xi);
  if (!surfaces.own_segment) settle_shared_point(surfaces, state, x_ref, u, p, best, best_distance, contact);
}

}  // namespace exdyn::contact
