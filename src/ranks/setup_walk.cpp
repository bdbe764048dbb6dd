// The walk over every chunk of every part: colours, centroids, the chunk graph and
// the partition (setup_parts.hpp).
#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>

#include "common/errors.hpp"
#include "element/corner_checks.hpp"
#include "element/element_family.hpp"
#include "material/elastic.hpp"
#include "material/material_law.hpp"
#include "mesh/mapped.hpp"
#include "mesh/mesh.hpp"
#include "model/memory_estimate.hpp"
#include "ranks/load_balance.hpp"
#include "ranks/setup_parts.hpp"

namespace exdyn::solver::setup {

// One pass over every element of every part, a chunk at a time. The colouring is
// build_schedule's: a chunk takes the lowest colour that no earlier chunk sharing a
// node has, with 64 colours per bit mask (past them, a new set of 64). Its masks are
// kept for a window of node ids only: a chunk's nodes lie within [its first element's
// corner 0, its last element's corner 6], both ascending with the chunk, so no later
// chunk comes back below the current one's lowest node.
void walk_part(const SetupPart& part, Chunks& chunks) {
  {
    auto first_node = [&](std::size_t c) { return part.element_nodes(std::uint32_t(c * chunk_size))[0]; };
    auto last_node = [&](std::size_t c) {
      return part.element_nodes(
          std::uint32_t(std::min<std::size_t>((c + 1) * chunk_size, part.element_count) - 1))[6];
    };
    // A box keeps the masks of a window of nodes (above). A part made whole keeps a
    // mask per node (its nodes in no such order); a cylinder or ball keeps those of the
    // nodes a later chunk may touch (each with its last element, purged as the chunks
    // pass it): a few layers of its blocks and their sides.
    const bool windowed = !part.built && !part.mapped;
    std::size_t span = 1;
    for (std::size_t c = 0; c < part.chunks && windowed; ++c)
      span = std::max<std::size_t>(span, last_node(c) - first_node(c) + 1);
    std::size_t window = 1;
    while (window < span) window *= 2;
    std::vector<std::uint64_t> masks(windowed ? window : (part.built ? part.node_count : 0), 0);
    struct Live {
      std::uint64_t mask = 0;
      std::uint32_t last_element = 0;
    };
    std::unordered_map<std::uint32_t, Live> live;
    std::size_t purge_at = 1024;
    auto mask = [&](std::uint32_t g) -> std::uint64_t& {
      if (windowed) return masks[g & (window - 1)];
      if (part.built) return masks[g - part.first_node];
      const auto [it, fresh] = live.try_emplace(g);
      if (fresh) it->second.last_element = part.elements_around(g).back();
      return it->second.mask;
    };
    std::int64_t highest = std::int64_t(part.first_node) - 1;  // nodes above it have no mask yet
    std::size_t base = 0, colours = 0;
    for (std::size_t c = 0; c < part.chunks; ++c) {
      const auto begin = std::uint32_t(c * chunk_size),
                 end = std::uint32_t(std::min<std::size_t>((c + 1) * chunk_size, part.element_count));
      std::array<double, 3> sum{};
      std::uint64_t taken = 0;
      for (std::uint32_t e = begin; e < end; ++e) {
        const std::array<int, 3> ijk = windowed ? part.element_ijk(e) : std::array<int, 3>{};
        const SetupPart::ElementNodes nodes = windowed ? SetupPart::ElementNodes{} : part.element_nodes(e);
        for (int k = 0; k < 8; ++k) {
          const std::array<double, 3> x =
              windowed ? part.point(part.corner(ijk, k)) : part.point_of(nodes[k]);
          for (std::size_t a = 0; a < 3; ++a) sum[a] += x[a];
        }
      }
      const double elements = double(end - begin);
      for (double& v : sum) v /= 8.0 * elements;
      chunks.centroid.push_back(sum);
      chunks.weight.push_back(elements);
      chunks.block_of.push_back(std::uint32_t(part.index));

      if (windowed) {
        for (std::int64_t g = highest + 1; g <= std::int64_t(last_node(c)); ++g)
          masks[std::size_t(g) & (window - 1)] = 0;
        highest = std::max<std::int64_t>(highest, last_node(c));
      }
      if (live.size() >= purge_at) {  // the nodes no chunk from here on touches
        std::erase_if(live, [&](const auto& entry) { return entry.second.last_element < begin; });
        purge_at = std::max<std::size_t>(1024, 2 * live.size());
      }
      for (std::uint32_t e = begin; e < end; ++e)
        for (const std::uint32_t g : part.element_nodes(e)) taken |= mask(g);
      if (taken == ~std::uint64_t{0}) {
        base += 64;
        std::fill(masks.begin(), masks.end(), std::uint64_t{0});
        live.clear();
        taken = 0;
      }
      int colour = 0;
      while (taken & (std::uint64_t{1} << colour)) ++colour;
      for (std::uint32_t e = begin; e < end; ++e)
        for (const std::uint32_t g : part.element_nodes(e)) mask(g) |= std::uint64_t{1} << colour;
      chunks.colour.push_back(int(base) + colour);
      colours = std::max(colours, base + std::size_t(colour) + 1);
    }
    chunks.colours.push_back(colours);
  }
}

// Every part walked (walk_part); a scattered part by rank 0, which sends its chunks'
// figures to every rank. Collective over comm where a part is scattered.
Chunks walk_chunks(const SetupParts& deck_parts, const mpi::Communicator* comm) {
  Chunks chunks;
  for (const SetupPart& part : deck_parts.list) {
    if (!part.scattered) {
      walk_part(part, chunks);
      continue;
    }
    Chunks section;
    Packer out;
    if (comm->root()) {
      walk_part(part, section);
      out.put(section.centroid);
      out.put(section.weight);
      out.put(section.colour);
      out.put(section.colours);
    }
    broadcast_bytes(*comm, out.bytes);
    Unpacker in{out.bytes};
    in.get(section.centroid);
    in.get(section.weight);
    in.get(section.colour);
    in.get(section.colours);
    chunks.centroid.insert(chunks.centroid.end(), section.centroid.begin(), section.centroid.end());
    chunks.weight.insert(chunks.weight.end(), section.weight.begin(), section.weight.end());
    chunks.block_of.insert(chunks.block_of.end(), part.chunks, std::uint32_t(part.index));
    chunks.colour.insert(chunks.colour.end(), section.colour.begin(), section.colour.end());
    chunks.colours.push_back(section.colours.at(0));
  }
  return chunks;
}

// The chunk graph of partition.cpp from the parts, part by part and chunk by chunk:
// each chunk's nodes (once each), the chunks around each of them, and how many of
// its nodes each other chunk shares. Parts share no node, so no edge joins two parts.
ChunkGraph chunk_graph_of(const SetupParts& deck_parts, const mpi::Communicator* comm);

// The partition of the chunks over `ranks` ranks: partition_chunks' on the whole model.
// comm: where a part is scattered (collective over it).
std::vector<int> partition_parts(const SetupParts& deck_parts, const Chunks& chunks, int ranks,
                                 Partitioning partitioning, const mpi::Communicator* comm) {
  if (partitioning == Partitioning::metis) {
    check_rank_count(ranks, deck_parts.chunks, deck_parts.elements);
    if (ranks == 1) return std::vector<int>(deck_parts.chunks, 0);
    return metis_chunks(chunk_graph_of(deck_parts, comm), chunks.weight, ranks);
  }
  return bisect_chunks(chunks.centroid, chunks.weight, chunks.block_of, ranks, deck_parts.elements);
}

// The chunks (global indices) of the elements around node g, ascending.
std::vector<std::size_t> chunks_at(const SetupPart& part, std::uint32_t g) {
  std::vector<std::size_t> out;
  for (const std::uint32_t e : part.elements_around(g)) {
    const std::size_t c = part.first_chunk + e / chunk_size;
    if (out.empty() || out.back() != c) out.push_back(c);  // elements ascending: chunks too
  }
  return out;
}

// A scattered part's rows come from rank 0, which holds it.
// A node's owner: the lowest rank of the chunks around it (of a scattered part on a
// rank other than 0, among its output rows: sent with its piece).
int owner_of_node(const SetupPart& part, std::uint32_t g, const Chunks& chunks) {
  if (part.piece) return part.piece->row_owner.at(g - part.first_node - part.piece->first_row);
  int owner = std::numeric_limits<int>::max();
  for (const std::size_t c : chunks_at(part, g)) owner = std::min(owner, chunks.rank[c]);
  return owner;
}

ChunkGraph chunk_graph_of(const SetupParts& deck_parts, const mpi::Communicator* comm) {
  ChunkGraph graph;
  graph.neighbours.resize(deck_parts.chunks);
  std::vector<std::uint32_t> count(deck_parts.chunks, 0), nodes, touched;
  for (const SetupPart& part : deck_parts.list) {
    const bool here = !part.scattered || comm->root();
    for (std::size_t c = 0; c < part.chunks && here; ++c) {
      const std::size_t me = part.first_chunk + c;
      nodes.clear();
      for (auto e = std::uint32_t(c * chunk_size);
           e < std::min<std::size_t>((c + 1) * chunk_size, part.element_count); ++e)
        for (const std::uint32_t g : part.element_nodes(e)) nodes.push_back(g);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      touched.clear();
      for (const std::uint32_t g : nodes)
        for (const std::size_t other : chunks_at(part, g))
          if (other != me && count[other]++ == 0) touched.push_back(std::uint32_t(other));
      std::sort(touched.begin(), touched.end());
      for (const std::uint32_t other : touched) {
        graph.neighbours[me].emplace_back(other, count[other]);
        count[other] = 0;
      }
    }
    if (!part.scattered) continue;
    Packer out;  // each chunk's neighbours and shared nodes, flat
    std::vector<std::uint64_t> sizes;
    std::vector<std::uint32_t> flat;  // (chunk, shared nodes) pairs
    if (comm->root())
      for (std::size_t c = 0; c < part.chunks; ++c) {
        const auto& row = graph.neighbours[part.first_chunk + c];
        sizes.push_back(row.size());
        for (const auto& [other, shared] : row) flat.push_back(other), flat.push_back(shared);
      }
    out.put(sizes);
    out.put(flat);
    broadcast_bytes(*comm, out.bytes);
    Unpacker in{out.bytes};
    in.get(sizes);
    in.get(flat);
    std::size_t at = 0;
    for (std::size_t c = 0; c < part.chunks; ++c) {
      auto& row = graph.neighbours[part.first_chunk + c];
      row.clear();
      for (std::size_t k = 0; k < sizes[c]; ++k, at += 2) row.emplace_back(flat[at], flat[at + 1]);
    }
  }
  return graph;
}

}  // namespace exdyn::solver::setup
