#include "contact/mortar_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "contact/single_surface.hpp"
#include "contact/slave_points.hpp"

namespace exdyn::contact {

namespace {

// Global search of segment pairs. A point x of slave segment s within the search distance
// d of master segment m now was within d + margin of it at the search (no node has moved
// more than margin / 2 since), and s's centre within R of x, R the largest extent of a
// slave segment (the diagonal of its box) at the search: so the centre lay in m's box
// inflated by d + margin + R. Of those pairs the bucket grid gives, the pairs kept are
// those whose boxes overlap once s's is inflated by d + margin.
}  // namespace

// The view's segments are the pass's (they change only where a search is asked for).
void set_mortar_view_segments(const ContactSurfaces& surfaces, MortarState& m) {
  m.view.slave_segments = surfaces.slave_segments;
  m.view.segments = surfaces.segments;
  m.view.moving_nodes = surfaces.moving_nodes;  // the scatter's slots (force_scatter.hpp)
  m.view.single_surface = surfaces.single_surface;
  m.view.first_part_segment = surfaces.first_part_segment;
}

namespace {

void search_segment_pairs(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                          ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u) {
  MortarState& m = state.mortar;
  const std::size_t n_slave = surfaces.slave_segments.size();
  auto position = [&](std::uint32_t node) {
    return std::array<double, 3>{x_ref.x[node] + u.x[node], x_ref.y[node] + u.y[node],
                                 x_ref.z[node] + u.z[node]};
  };
  const double capture = settings.search_distance + settings.margin;
  segment_boxes(position, surfaces.slave_segments, capture, m.slave_boxes);
  m.centres.resize(n_slave);
  double extent = 0.0;
  for (std::size_t s = 0; s < n_slave; ++s) {
    const Vec3 c = contact::position(current_segment(surfaces.slave_segments[s], x_ref, u), Xi{0.0, 0.0});
    m.centres.x[s] = c.x, m.centres.y[s] = c.y, m.centres.z[s] = c.z;
    double diagonal = 0.0;  // of the box without the capture
    for (int k = 0; k < 3; ++k) {
      const double side =
          m.slave_boxes[s].hi[std::size_t(k)] - m.slave_boxes[s].lo[std::size_t(k)] - 2.0 * capture;
      diagonal += side * side;
    }
    extent = std::max(extent, std::sqrt(diagonal));
  }
  segment_boxes(position, surfaces.segments, capture + extent, state.boxes);
  bucket_search(m.centres, state.boxes, settings.cell_size, state.workspace, m.pairs);
  segment_boxes(position, surfaces.segments, 0.0, m.master_boxes);
  auto overlap = [](const Box& a, const Box& b) {
    for (std::size_t k = 0; k < 3; ++k)
      if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
    return true;
  };
  std::erase_if(m.pairs, [&](const CandidatePair& pair) {
    return !overlap(m.slave_boxes[pair.point], m.master_boxes[pair.segment]);
  });
  // A single surface: no pair of segments that share a node or face the same way
  // (single_surface.hpp; a point's own rule then runs on each piece's points).
  if (surfaces.single_surface)
    std::erase_if(m.pairs, [&](const CandidatePair& pair) {
      return segments_excluded(surfaces.slave_segments[pair.point], surfaces.segments[pair.segment], x_ref,
                               u);
    });
  m.pair_begin.assign(n_slave + 1, 0);
  for (const CandidatePair& pair : m.pairs) ++m.pair_begin[pair.point + 1];
  for (std::size_t s = 0; s < n_slave; ++s) m.pair_begin[s + 1] += m.pair_begin[s];

  state.moving_at_build.resize(surfaces.moving_nodes.size());
  for (std::size_t i = 0; i < surfaces.moving_nodes.size(); ++i) {
    const Vec3 x = current_position(x_ref, u, surfaces.moving_nodes[i]);
    state.moving_at_build.x[i] = x.x;
    state.moving_at_build.y[i] = x.y;
    state.moving_at_build.z[i] = x.z;
  }
  state.built = true;
  ++state.rebuilds;
  set_mortar_view_segments(surfaces, m);
}

// Cuts the slave segments chunk by chunk on the threads, each chunk into its own list
// (m.chunk_points), and counts each segment's points: m.point_begin, ascending. The lists
// joined in chunk order are the same points on any number of threads.
void cut_segments(const ContactSurfaces& surfaces, const ContactPassSettings& settings, MortarState& m,
                  const NodalVectors& x_ref, const NodalVectors& u) {
  const std::size_t n_slave = surfaces.slave_segments.size();
  const PieceRule rule = piece_rule(surfaces.triangle_points);
  const std::size_t chunks = (n_slave + mortar_chunk - 1) / mortar_chunk;
  if (m.chunk_points.size() < chunks) m.chunk_points.resize(chunks);
  m.point_begin.assign(n_slave + 1, 0);
  const auto chunk_count = static_cast<std::ptrdiff_t>(chunks);
#pragma omp parallel for schedule(dynamic, 1) if (chunk_count > 1 && n_slave >= 256)
  for (std::ptrdiff_t k = 0; k < chunk_count; ++k) {
    std::vector<MortarState::Piece>& points = m.chunk_points[std::size_t(k)];
    points.clear();
    std::array<MortarPoint, max_mortar_points_per_pair> scratch;
    const std::size_t end = std::min(n_slave, std::size_t(k + 1) * mortar_chunk);
    for (std::size_t s = std::size_t(k) * mortar_chunk; s < end; ++s) {
      const SlaveFacet slave = slave_facet(current_segment(surfaces.slave_segments[s], x_ref, u));
      const std::size_t before = points.size();
      for (std::size_t c = m.pair_begin[s]; c < m.pair_begin[s + 1]; ++c) {
        const std::uint32_t master = m.pairs[c].segment;
        const int count = mortar_points(slave, current_segment(surfaces.segments[master], x_ref, u), rule,
                                        settings.search_distance, scratch.data());
        for (int i = 0; i < count; ++i) points.push_back({scratch[std::size_t(i)], master, std::uint32_t(i)});
      }
      m.point_begin[s + 1] = points.size() - before;
    }
  }
  for (std::size_t s = 0; s < n_slave; ++s) m.point_begin[s + 1] += m.point_begin[s];
}

// This step's points as the view's quadrature points, each with its one candidate (its
// piece's master segment, from where the plane's projection met it: the starting point
// of `previous`), its stiffness kappa w, length and dashpot mass.
void fill_view(const ContactSurfaces& surfaces, ContactPassState& state) {
  MortarState& m = state.mortar;
  ContactSurfaces& view = m.view;
  const std::size_t n_slave = surfaces.slave_segments.size(), n_points = m.point_begin[n_slave];
  view.quadrature = true;
  view.own_segment = true;
  view.quadrature_points.resize(n_points);
  view.stiffness.resize(n_points);
  view.normal_length.resize(n_points);
  view.point_mass.resize(n_points);
  if (view.single_surface) view.first_part_point.resize(n_points);
  std::swap(m.identity, m.previous_identity);
  m.identity.resize(n_points);
  state.candidates.resize(n_points);
  state.previous_xi.resize(n_points);
  const auto chunk_count = static_cast<std::ptrdiff_t>((n_slave + mortar_chunk - 1) / mortar_chunk);
#pragma omp parallel for schedule(static) if (chunk_count > 1 && n_slave >= 256)
  for (std::ptrdiff_t k = 0; k < chunk_count; ++k) {
    const std::size_t first_segment = std::size_t(k) * mortar_chunk;
    const std::size_t end = std::min(n_slave, first_segment + mortar_chunk);
    std::size_t p = m.point_begin[first_segment];
    for (std::size_t s = first_segment; s < end; ++s)
      for (; p < m.point_begin[s + 1]; ++p) {
        const MortarState::Piece& piece = m.chunk_points[std::size_t(k)][p - m.point_begin[first_segment]];
        const MortarPoint& point = piece.point;
        view.quadrature_points[p] = {std::uint32_t(s), point.slave_xi, point.weight};
        view.stiffness[p] = surfaces.segment_kappa[s] * point.weight;
        view.normal_length[p] = surfaces.segment_length[s];
        // The dashpot's reduced mass: mu w, 1 / mu = 1 / mu_s + 1 / mu_m.
        view.point_mass[p] =
            point.weight / (surfaces.slave_area_per_mass[s] + surfaces.master_area_per_mass[piece.master]);
        if (view.single_surface) view.first_part_point[p] = surfaces.first_part_point[s];
        m.identity[p] = {std::uint32_t(s), piece.master, piece.index};
        state.candidates[p] = {std::uint32_t(p), piece.master};
        state.previous_xi[p] = point.master_xi;
      }
  }
  state.point_begin.resize(n_points + 1);
  for (std::size_t p = 0; p <= n_points; ++p) state.point_begin[p] = p;
}

// Friction: each point takes the stick anchor of the last step's point of the same piece
// (both lists of pieces ascend: a merge); a point of a new piece has none.
void carry_anchors(ContactPassState& state) {
  MortarState& m = state.mortar;
  std::swap(state.anchors, m.previous_anchors);
  state.anchors.assign(m.identity.size(), Anchor{});
  std::size_t old = 0;
  for (std::size_t p = 0; p < m.identity.size(); ++p) {
    while (old < m.previous_identity.size() && m.previous_identity[old] < m.identity[p]) ++old;
    if (old < m.previous_identity.size() && m.previous_identity[old] == m.identity[p] &&
        old < m.previous_anchors.size())
      state.anchors[p] = m.previous_anchors[old];
  }
}

}  // namespace

void run_mortar_pass(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                     ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u,
                     const NodalVectors& v, const std::vector<double>& mass, NodalVectors& force,
                     std::vector<double>& gap, ContactStatistics& statistics, ContactPhaseSeconds& seconds,
                     RecordSink* records, bool search_when_moved) {
  MortarState& m = state.mortar;
  {
    ScopedTimer timer(seconds.global_search);
    if (search_when_moved ? largest_motion_since_build(surfaces, state, x_ref, u) > 0.5 * settings.margin
                          : !state.built)
      search_segment_pairs(surfaces, settings, state, x_ref, u);
  }
  {
    ScopedTimer timer(seconds.segmentation);
    cut_segments(surfaces, settings, state.mortar, x_ref, u);
    fill_view(surfaces, state);
    if (settings.friction.enabled) carry_anchors(state);
  }
  if (records == nullptr) {
    run_contact_pass(m.view, settings, state, x_ref, u, v, mass, force, gap, statistics, seconds, nullptr,
                     false);
    return;
  }
  // A point's record key: its slave segment's, then its place among the segment's points.
  const std::vector<std::uint64_t>* segment_keys = records->point_keys;
  m.point_keys.resize(m.identity.size());
  for (std::size_t s = 0; s + 1 < m.point_begin.size(); ++s)
    for (std::size_t p = m.point_begin[s]; p < m.point_begin[s + 1]; ++p) {
      const std::uint64_t place = p - m.point_begin[s];
      EXDYN_ASSERT(place < (std::uint64_t(1) << mortar_key_bits));
      m.point_keys[p] = (*segment_keys)[s] << mortar_key_bits | place;
    }
  records->point_keys = &m.point_keys;
  run_contact_pass(m.view, settings, state, x_ref, u, v, mass, force, gap, statistics, seconds, records,
                   false);
  records->point_keys = segment_keys;
}

}  // namespace exdyn::contact
