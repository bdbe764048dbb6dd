// The scatter of a contact pass's point forces, alone or in chunks on the threads
// (force_scatter.hpp).
#include "contact/force_scatter.hpp"

#include <algorithm>
#include <atomic>
#include <limits>

#include "common/errors.hpp"
#include "common/parallel.hpp"
#include "contact/slave_points.hpp"

namespace exdyn::contact {

namespace {

// A node's mark: the lowest chunk that writes it in this call, under the call's stamp,
// ((2^32 - 1 - stamp) << 32) | chunk: a later call's marks are lower, so the marks of
// earlier calls need no clearing (the least wins).
constexpr std::uint64_t unmarked = std::numeric_limits<std::uint64_t>::max();
std::uint64_t mark_of(std::uint32_t stamp, std::size_t chunk) {
  return (std::uint64_t(std::numeric_limits<std::uint32_t>::max() - stamp) << 32) | std::uint64_t(chunk);
}

// Which of its writes point_writes makes: keep(false, i) for slave node i, keep(true, i)
// for master node i.
constexpr bool slave_node = false, master_node = true;

// Point p's writes, in the order of one process, to the nodes `keep` accepts: its gap
// on its slave nodes, then, pressed, +w_I F on its slave nodes and -N_i F on its master
// segment's nodes (f -= N F: records add -(N F), the same bits).
template <class Target, class Keep>
void point_writes(const ContactSurfaces& surfaces, const ContactPassState& state, std::size_t p,
                  Target& target, Keep keep) {
  const auto& contact = state.contacts[p];
  if (contact.segment < 0) return;
  const SlaveSide slave = slave_side(surfaces, p);
  for (int i = 0; i < slave.count; ++i)
    if (keep(slave_node, i)) target.gap(p, i, slave.nodes[std::size_t(i)], contact.gap);
  if (contact.gap >= 0.0) return;
  const Vec3 F = state.point_force[p];
  for (int i = 0; i < slave.count; ++i)
    if (keep(slave_node, i))
      target.slave(p, i, slave.nodes[std::size_t(i)], slave.weights[std::size_t(i)], F);
  const SegmentNodes& master = surfaces.segments[static_cast<std::size_t>(contact.segment)];
  const std::array<double, 8> N = shape_functions(master.type, contact.xi);
  for (int i = 0; i < node_count(master.type); ++i)
    if (keep(master_node, i)) target.master(p, i, master.nodes[std::size_t(i)], N[std::size_t(i)], F);
}

const auto every_write = [](bool, int) { return true; };

struct ArrayTarget {
  NodalVectors& force;
  std::vector<double>& gap_of;
  void gap(std::size_t, int, std::uint32_t node, double g) { gap_of[node] = std::min(gap_of[node], g); }
  void slave(std::size_t, int, std::uint32_t node, double w, Vec3 F) {
    force.x[node] += w * F.x;
    force.y[node] += w * F.y;
    force.z[node] += w * F.z;
  }
  void master(std::size_t, int, std::uint32_t node, double N, Vec3 F) {
    force.x[node] -= N * F.x;
    force.y[node] -= N * F.y;
    force.z[node] -= N * F.z;
  }
};

struct RecordTarget {
  RecordSink& records;
  void gap(std::size_t p, int i, std::uint32_t node, double g) { records.gap(p, i, node, g); }
  void slave(std::size_t p, int i, std::uint32_t node, double w, Vec3 F) {
    records.add(p, i, node, w * F.x, w * F.y, w * F.z);
  }
  void master(std::size_t p, int i, std::uint32_t node, double N, Vec3 F) {
    records.add(p, 8 + i, node, -(N * F.x), -(N * F.y), -(N * F.z));
  }
};

// The slots (places in surfaces.moving_nodes, the pass's nodes) of each slave node (slave
// nodes) or of each slave segment's nodes (Gauss points, 8 a segment) and of each master
// segment's nodes (8 a segment): fixed until the pass's next candidate search (where a
// view's segments may change), made at the first call after it. The marks are kept
// per slot: a few kB that stay in the cache, where marks per node of the model would
// be a sweep of the memory each step.
void make_slots(const ContactSurfaces& surfaces, long rebuilds, ScatterScratch& scratch) {
  const std::vector<std::uint32_t>& nodes = surfaces.moving_nodes;
  auto slot = [&](std::uint32_t node) {
    const auto at = std::lower_bound(nodes.begin(), nodes.end(), node);
    EXDYN_ASSERT(at != nodes.end() && *at == node);  // every node of the pass moves with it
    return std::uint32_t(at - nodes.begin());
  };
  // A segment or slave node off the surface (erosion: ContactSurfaces::segment_live) has
  // no contact until the next search, and no slot.
  auto segment_slots = [&](const std::vector<SegmentNodes>& segments, std::vector<std::uint32_t>& slots,
                           bool master) {
    slots.assign(8 * segments.size(), 0);
    for (std::size_t s = 0; s < segments.size(); ++s) {
      if (master && !surfaces.segment_on(s)) continue;
      for (int i = 0; i < node_count(segments[s].type); ++i)
        slots[8 * s + std::size_t(i)] = slot(segments[s].nodes[std::size_t(i)]);
    }
  };
  if (surfaces.quadrature) {
    segment_slots(surfaces.slave_segments, scratch.slave_slots, false);
  } else {
    scratch.slave_slots.assign(surfaces.slave_nodes.size(), 0);
    for (std::size_t p = 0; p < surfaces.slave_nodes.size(); ++p)
      if (surfaces.point_on(p)) scratch.slave_slots[p] = slot(surfaces.slave_nodes[p]);
  }
  segment_slots(surfaces.segments, scratch.segment_slots, true);
  scratch.first_chunk.assign(nodes.size(), unmarked);
  scratch.stamp = 0;
  scratch.rebuilds = rebuilds;
}

// Lowers first_chunk[slot] to `mark`, if it is lower (any thread may lower it: the least wins).
void lower(std::vector<std::uint64_t>& first_chunk, std::uint32_t slot, std::uint64_t mark) {
  std::atomic_ref<std::uint64_t> first(first_chunk[slot]);
  std::uint64_t seen = first.load(std::memory_order_relaxed);
  while (mark < seen && !first.compare_exchange_weak(seen, mark, std::memory_order_relaxed)) {
  }
}

}  // namespace

void scatter_in_point_order(const ContactSurfaces& surfaces, const ContactPassState& state,
                            NodalVectors& force, std::vector<double>& gap) {
  ArrayTarget target{force, gap};
  for (std::size_t p = 0; p < state.contacts.size(); ++p)
    point_writes(surfaces, state, p, target, every_write);
}

void scatter_to_records(const ContactSurfaces& surfaces, const ContactPassState& state, RecordSink& records) {
  RecordTarget target{records};
  for (std::size_t p = 0; p < state.contacts.size(); ++p)
    point_writes(surfaces, state, p, target, every_write);
}

void scatter_by_chunks(const ContactSurfaces& surfaces, const ContactPassState& state, NodalVectors& force,
                       std::vector<double>& gap, std::size_t chunk, ScatterScratch& scratch) {
  const std::size_t points = state.contacts.size();
  if (scratch.rebuilds != state.rebuilds || scratch.stamp == std::numeric_limits<std::uint32_t>::max())
    make_slots(surfaces, state.rebuilds, scratch);
  const std::uint32_t stamp = ++scratch.stamp;
  std::vector<std::uint64_t>& first_chunk = scratch.first_chunk;
  // The slot of point p's write (master: of its segment's node i).
  auto slot_of = [&](std::size_t p, bool master, int i) {
    if (master) return scratch.segment_slots[8 * std::size_t(state.contacts[p].segment) + std::size_t(i)];
    if (!surfaces.quadrature) return scratch.slave_slots[p];
    return scratch.slave_slots[8 * std::size_t(surfaces.quadrature_points[p].segment) + std::size_t(i)];
  };
  scratch.late.resize(chunk_count(points, chunk));
  ArrayTarget target{force, gap};
  // The marks: each node's first chunk, from the slots of each point's writes alone (no
  // weights or shape functions: point_writes' nodes, not its values).
  auto mark_point = [&](std::size_t p, std::uint64_t mark) {
    const auto& contact = state.contacts[p];
    if (contact.segment < 0) return;
    const int slaves = surfaces.quadrature
                           ? node_count(surfaces.slave_segments[surfaces.quadrature_points[p].segment].type)
                           : 1;
    for (int i = 0; i < slaves; ++i) lower(first_chunk, slot_of(p, slave_node, i), mark);
    if (contact.gap >= 0.0) return;
    for (int i = 0; i < node_count(surfaces.segments[std::size_t(contact.segment)].type); ++i)
      lower(first_chunk, slot_of(p, master_node, i), mark);
  };
  for_each_chunk(
      points,
      [&](std::size_t begin, std::size_t end, std::size_t c) {
        const std::uint64_t mark = mark_of(stamp, c);
        for (std::size_t p = begin; p < end; ++p) mark_point(p, mark);
      },
      chunk);
  // Each chunk writes the nodes it is the first of, its points in order, and keeps
  // the points with a write left for the ordered phase.
  for_each_chunk(
      points,
      [&](std::size_t begin, std::size_t end, std::size_t c) {
        const std::uint64_t mark = mark_of(stamp, c);
        std::vector<std::uint32_t>& late = scratch.late[c];
        late.clear();
        for (std::size_t p = begin; p < end; ++p) {
          bool left = false;
          point_writes(surfaces, state, p, target, [&](bool master, int i) {
            const bool first = first_chunk[slot_of(p, master, i)] == mark;
            left = left || !first;
            return first;
          });
          if (left) late.push_back(std::uint32_t(p));
        }
      },
      chunk);
  // Then the later chunks' writes to those nodes, alone, in point order.
  for (std::size_t c = 0; c < scratch.late.size(); ++c) {
    const std::uint64_t mark = mark_of(stamp, c);
    for (const std::uint32_t p : scratch.late[c])
      point_writes(surfaces, state, p, target,
                   [&](bool master, int i) { return first_chunk[slot_of(p, master, i)] != mark; });
  }
}

}  // namespace exdyn::contact
