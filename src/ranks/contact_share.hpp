// What the contact's files on many ranks share (distributed_contact.cpp, ghost_search.cpp):
// the messages' tags and payloads, the exchange of items between all ranks, the
// store's ids and the search that brings a pass's ghost segments.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "common/mpi.hpp"
#include "common/nodal_vectors.hpp"
#include "common/timer.hpp"
#include "contact/contact_pass.hpp"
#include "ranks/distributed_contact.hpp"

namespace exdyn::solver::shares {
// Tags of the contact's point-to-point messages, apart from the force exchange's.
// (Within the 32767 every MPI allows; the force exchange's count from 1, a few per block.)
constexpr int record_tag = 30000, total_tag = 30001, ghost_tag = 30002;  // + the pass

template <class T>
std::size_t index_in(const std::vector<T>& sorted, T value) {
  const auto at = std::lower_bound(sorted.begin(), sorted.end(), value);
  return at != sorted.end() && *at == value ? std::size_t(at - sorted.begin()) : sorted.size();
}

// A segment as it travels at a search: its index in the whole pass, its nodes (global
// ids) and what lies past its edges.
struct SegmentPayload {
  std::uint32_t id = 0;
  contact::SegmentNodes nodes;
  contact::SegmentEdges edges;
  double area_per_mass = 0.0;  // mortar: the mean a / m of its nodes (ContactSurfaces), m^2/kg
  // A single surface: whether it lies on the first part, the segments across its
  // edges by index in the whole pass (ContactSurfaces::edge_neighbours) and its face
  // (ContactSurfaces::segment_face; 0 where the pass has none).
  std::uint8_t first_part = 0;
  std::array<std::int32_t, 4> neighbours{-1, -1, -1, -1};
  std::uint32_t face = 0;
};
// A node the receiver does not hold: its owner and its data at the search.
struct NodePayload {
  std::uint32_t global = 0;
  int owner = 0;
  double x_ref[3], u[3], v[3], mass;
};
static_assert(std::is_trivially_copyable_v<SegmentPayload> && std::is_trivially_copyable_v<NodePayload> &&
              std::is_trivially_copyable_v<contact::ForceRecord>);

// Items of type T to every rank (MPI_Alltoallv as bytes): out[r] to rank r; returns
// what each rank sent here. Counts the bytes and messages sent.
template <class T>
std::vector<std::vector<T>> all_to_all(DistributedContact& dc, const std::vector<std::vector<T>>& out) {
  const auto ranks = std::size_t(dc.comm.size);
  std::vector<int> send_counts(ranks), receive_counts(ranks), send_at(ranks, 0), receive_at(ranks, 0);
  std::vector<T> flat;
  for (std::size_t r = 0; r < ranks; ++r) {
    send_counts[r] = int(sizeof(T) * out[r].size());
    send_at[r] = int(sizeof(T) * flat.size());
    flat.insert(flat.end(), out[r].begin(), out[r].end());
    if (int(r) != dc.comm.rank && !out[r].empty())
      dc.messages_sent += 1, dc.bytes_sent += double(send_counts[r]);
  }
  std::vector<T> in;
  {
    const ScopedTimer timer(dc.wait_seconds);
    mpi::check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, dc.comm.comm),
               "MPI_Alltoall of the contact's counts");
    for (std::size_t r = 1; r < ranks; ++r) receive_at[r] = receive_at[r - 1] + receive_counts[r - 1];
    in.resize(std::size_t(receive_at[ranks - 1] + receive_counts[ranks - 1]) / sizeof(T));
    mpi::check(MPI_Alltoallv(flat.data(), send_counts.data(), send_at.data(), MPI_BYTE, in.data(),
                             receive_counts.data(), receive_at.data(), MPI_BYTE, dc.comm.comm),
               "MPI_Alltoallv of the contact's data");
  }
  std::vector<std::vector<T>> from(ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    const auto first = in.begin() + receive_at[r] / std::ptrdiff_t(sizeof(T));
    from[r].assign(first, first + receive_counts[r] / std::ptrdiff_t(sizeof(T)));
  }
  return from;
}

// A single surface's view: its node corners and edge neighbours from indices in the whole
// pass (PassShare::own) to those of the view's segments (PassShare::known); a neighbour
// not in the view is -1 (no segment the point may touch there).
void index_single_surface(PassShare& share);

// A surface that follows erosion (PassShare::whole): the view's segments and points on
// or off the surface as the whole pass's (after the view changed).
void apply_life(PassShare& share);

// A node's place in the store (global id in), or store.global.size().
std::size_t store_index(const ContactStore& store, std::uint32_t node);

// The ids of a segment's nodes in the store (global ids in, store ids out).
contact::SegmentNodes in_store(contact::SegmentNodes segment, const ContactStore& store);

// A new candidate search of one pass (every rank together): the box exchange, the
// ghost segments and their nodes, the view and the store; the pass's candidates and
// anchors follow their segments into the new view, and the pass searches again.
void search_again(DistributedContact& dc, PassShare& share, const contact::ContactPassSettings& settings,
                  contact::ContactPassState& state, const std::vector<std::uint32_t>& global_node,
                  const NodalVectors& x_ref, const std::vector<double>& mass, const NodalVectors& u,
                  const NodalVectors& v);

// A restart (checkpoint_ranks.cpp): the view made of the own segments and the segments
// `needed` (whole-pass indices, ascending: every segment the pass's state names) from
// the ranks that own them, with the store and the ghost links; the state, whose
// segments are whole-pass indices, is renumbered to the view. Collective over dc.comm.
void restore_view(DistributedContact& dc, PassShare& share, const std::vector<std::uint32_t>& needed,
                  contact::ContactPassState& state, const std::vector<std::uint32_t>& global_node,
                  const NodalVectors& x_ref, const std::vector<double>& mass, const NodalVectors& u,
                  const NodalVectors& v);

}  // namespace exdyn::solver::shares
