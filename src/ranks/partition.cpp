// The partition of the chunks over the ranks: recursive coordinate bisection of the
// chunk centroids, or METIS on the graph of chunks (decomposition.hpp, docs/parallel.md).
#include <metis.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <numeric>
#include <string>

#include "common/errors.hpp"
#include "ranks/decomposition.hpp"

namespace exdyn::solver {

namespace {

// The chunks, block after block: each chunk's nodes (global ids, ascending, once).
std::vector<std::vector<std::uint32_t>> chunk_nodes(const Model& model) {
  std::vector<std::vector<std::uint32_t>> result;
  for (const element::ElementBlock& block : model.blocks)
    for (std::size_t c = 0; c + 1 < block.chunk_begin.size(); ++c) {
      const auto n = std::size_t(block.nodes_per_element);
      std::vector<std::uint32_t> nodes(block.connectivity + n * block.chunk_begin[c],
                                       block.connectivity + n * block.chunk_begin[c + 1]);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      result.push_back(std::move(nodes));
    }
  return result;
}

ChunkGraph chunk_graph(const std::vector<std::vector<std::uint32_t>>& nodes_of, std::size_t node_count) {
  // The chunks at each node, then the pairs they make.
  std::vector<std::uint32_t> start(node_count + 1, 0);
  for (const auto& nodes : nodes_of)
    for (const std::uint32_t n : nodes) ++start[n + 1];
  for (std::size_t n = 0; n < node_count; ++n) start[n + 1] += start[n];
  std::vector<std::uint32_t> at_node(start[node_count]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t c = 0; c < nodes_of.size(); ++c)
    for (const std::uint32_t n : nodes_of[c]) at_node[fill[n]++] = c;
  ChunkGraph graph;
  graph.neighbours.resize(nodes_of.size());
  std::vector<std::uint32_t> count(nodes_of.size(), 0);
  for (std::uint32_t c = 0; c < nodes_of.size(); ++c) {
    std::vector<std::uint32_t> touched;
    for (const std::uint32_t n : nodes_of[c])
      for (std::uint32_t k = start[n]; k < start[n + 1]; ++k) {
        const std::uint32_t other = at_node[k];
        if (other == c) continue;
        if (count[other]++ == 0) touched.push_back(other);
      }
    std::sort(touched.begin(), touched.end());
    for (const std::uint32_t other : touched) {
      graph.neighbours[c].emplace_back(other, count[other]);
      count[other] = 0;
    }
  }
  return graph;
}

}  // namespace

std::vector<int> metis_chunks(const ChunkGraph& graph, const std::vector<double>& weight, int ranks) {
  const std::size_t chunks = graph.neighbours.size();
  std::vector<idx_t> xadj{0}, adjncy, adjwgt, vwgt;
  for (std::size_t c = 0; c < chunks; ++c) {
    for (const auto& [other, shared] : graph.neighbours[c]) {
      adjncy.push_back(idx_t(other));
      adjwgt.push_back(idx_t(shared));
    }
    xadj.push_back(idx_t(adjncy.size()));
    vwgt.push_back(idx_t(weight[c]));
  }
  idx_t vertices = idx_t(chunks), constraints = 1, parts = ranks, objective = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;  // the same partition on every rank and every run
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_CONTIG] = 0;
  std::vector<idx_t> part(chunks, 0);
  real_t imbalance = 1.03f;
  const int status =
      ranks == 2
          ? METIS_PartGraphRecursive(&vertices, &constraints, xadj.data(), adjncy.data(), vwgt.data(),
                                     nullptr, adjwgt.data(), &parts, nullptr, &imbalance, options, &objective,
                                     part.data())
          : METIS_PartGraphKway(&vertices, &constraints, xadj.data(), adjncy.data(), vwgt.data(), nullptr,
                                adjwgt.data(), &parts, nullptr, &imbalance, options, &objective, part.data());
  if (status != METIS_OK)
    throw InputError("METIS could not partition " + std::to_string(chunks) + " chunks over " +
                     std::to_string(ranks) + " ranks (status " + std::to_string(status) +
                     "); use --partition bisection");
  std::vector<int> rank_of(part.begin(), part.end());
  std::vector<int> chunks_on(std::size_t(ranks), 0);
  for (const int r : rank_of) ++chunks_on[std::size_t(r)];
  for (int r = 0; r < ranks; ++r)
    if (chunks_on[std::size_t(r)] == 0)
      throw InputError("METIS left rank " + std::to_string(r) + " of " + std::to_string(ranks) +
                       " without a chunk of the " + std::to_string(chunks) +
                       "; run on fewer ranks or use --partition bisection");
  return rank_of;
}

PartitionFigures partition_figures(const Model& model, const std::vector<int>& chunk_rank) {
  const std::vector<std::vector<std::uint32_t>> nodes_of = chunk_nodes(model);
  const ChunkGraph graph = chunk_graph(nodes_of, model.mesh.node_count());
  PartitionFigures figures;
  for (std::size_t c = 0; c < nodes_of.size(); ++c)
    for (const auto& [other, shared] : graph.neighbours[c])
      if (other > c && chunk_rank[c] != chunk_rank[other]) figures.edge_cut += long(shared);
  std::vector<int> rank_at(model.mesh.node_count(), -1);
  std::vector<char> shared(model.mesh.node_count(), 0);
  for (std::size_t c = 0; c < nodes_of.size(); ++c)
    for (const std::uint32_t n : nodes_of[c]) {
      if (rank_at[n] >= 0 && rank_at[n] != chunk_rank[c]) shared[n] = 1;
      rank_at[n] = chunk_rank[c];
    }
  for (const char s : shared) figures.shared_nodes += s;
  return figures;
}

std::vector<int> partition_chunks(const Model& model, int ranks, Partitioning partitioning,
                                  const std::vector<double>& costs) {
  // The chunks, block after block: centroid (mean of their elements' corner nodes, m)
  // and weight (elements, or their measured costs).
  std::vector<std::array<double, 3>> centroid;
  std::vector<double> weight;
  std::vector<std::uint32_t> block_of;
  const mesh::Mesh& mesh = model.mesh;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const element::ElementBlock& block = model.blocks[b];
    for (std::size_t c = 0; c + 1 < block.chunk_begin.size(); ++c) {
      std::array<double, 3> sum{};
      for (std::uint32_t e = block.chunk_begin[c]; e < block.chunk_begin[c + 1]; ++e) {
        const std::uint32_t* nodes = block.connectivity + std::size_t(block.nodes_per_element) * e;
        for (int k = 0; k < 8; ++k)
          for (int x = 0; x < 3; ++x) sum[std::size_t(x)] += mesh.x_ref.component(x)[nodes[k]];
      }
      const double elements = double(block.chunk_begin[c + 1] - block.chunk_begin[c]);
      for (double& v : sum) v /= 8.0 * elements;
      centroid.push_back(sum);
      weight.push_back(elements);
      block_of.push_back(std::uint32_t(b));
    }
  }
  const std::size_t chunks = centroid.size();
  if (!costs.empty()) weigh_by_costs(weight, costs);
  if (partitioning == Partitioning::metis) {
    check_rank_count(ranks, chunks, mesh.element_count());
    if (ranks == 1) return std::vector<int>(chunks, 0);
    return metis_chunks(chunk_graph(chunk_nodes(model), mesh.node_count()), weight, ranks);
  }
  return bisect_chunks(centroid, weight, block_of, ranks, mesh.element_count());
}

void weigh_by_costs(std::vector<double>& weight, const std::vector<double>& costs) {
  EXDYN_ASSERT(costs.size() == weight.size());
  double total_cost = 0.0, total_elements = 0.0;
  for (std::size_t c = 0; c < weight.size(); ++c) total_cost += costs[c], total_elements += weight[c];
  for (std::size_t c = 0; c < weight.size(); ++c)
    weight[c] = total_cost > 0.0 ? std::max(costs[c] * total_elements / total_cost, 1.0) : weight[c];
}

void check_rank_count(int ranks, std::size_t chunks, std::size_t elements) {
  if (ranks < 1 || static_cast<std::size_t>(ranks) > chunks)
    throw InputError(
        std::to_string(ranks) + " MPI ranks for a mesh of " + std::to_string(elements) + " elements in " +
        std::to_string(chunks) + " chunks of at most " + std::to_string(element::element_chunk) +
        ": every rank needs a chunk (docs/parallel.md); run on at most " + std::to_string(chunks) + " ranks");
}

std::vector<int> bisect_chunks(const std::vector<std::array<double, 3>>& centroid,
                               const std::vector<double>& weight, const std::vector<std::uint32_t>& block_of,
                               int ranks, std::size_t elements) {
  const std::size_t chunks = centroid.size();
  check_rank_count(ranks, chunks, elements);
  std::vector<std::uint32_t> order(chunks);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<int> rank_of(chunks, 0);
  // Chunks order[begin, end) go to ranks [first, first + count).
  auto bisect = [&](auto&& self, std::size_t begin, std::size_t end, int first, int count) -> void {
    if (count == 1) {
      for (std::size_t k = begin; k < end; ++k) rank_of[order[k]] = first;
      return;
    }
    std::array<double, 3> low, high;
    low.fill(std::numeric_limits<double>::infinity());
    high.fill(-std::numeric_limits<double>::infinity());
    double total = 0.0;
    for (std::size_t k = begin; k < end; ++k) {
      total += weight[order[k]];
      for (std::size_t c = 0; c < 3; ++c) {
        low[c] = std::min(low[c], centroid[order[k]][c]);
        high[c] = std::max(high[c], centroid[order[k]][c]);
      }
    }
    std::size_t axis = 0;
    for (std::size_t c = 1; c < 3; ++c)
      if (high[c] - low[c] > high[axis] - low[axis]) axis = c;
    // The chunks of a block are strips of consecutive elements (a part's x-rows), whose
    // centroids barely differ across the strips: sorted by coordinate alone, two blocks
    // side by side along the axis would have their chunks interleaved by that noise. So
    // the blocks are ordered by their mean along the axis, and each block's chunks along
    // the block's own longest spread (for one block: plain bisection).
    std::map<std::uint32_t, std::array<double, 3>> block_low, block_high;
    std::map<std::uint32_t, std::pair<double, double>> block_sum;  // weighted coordinate, weight
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t u = order[k], b = block_of[u];
      auto [lo, new_lo] = block_low.try_emplace(b, centroid[u]);
      auto [hi, new_hi] = block_high.try_emplace(b, centroid[u]);
      for (std::size_t c = 0; c < 3; ++c) {
        lo->second[c] = std::min(lo->second[c], centroid[u][c]);
        hi->second[c] = std::max(hi->second[c], centroid[u][c]);
      }
      block_sum[b].first += weight[u] * centroid[u][axis];
      block_sum[b].second += weight[u];
    }
    std::map<std::uint32_t, std::size_t> block_axis;
    std::map<std::uint32_t, double> block_mean;
    for (const auto& [b, lo] : block_low) {
      const auto& hi = block_high[b];
      std::size_t a = 0;
      for (std::size_t c = 1; c < 3; ++c)
        if (hi[c] - lo[c] > hi[a] - lo[a]) a = c;
      block_axis[b] = a;
      block_mean[b] = block_sum[b].first / block_sum[b].second;
    }
    auto key = [&](std::uint32_t u) {
      const std::uint32_t b = block_of[u];
      return std::tuple(block_mean[b], b, centroid[u][block_axis[b]], u);
    };
    std::sort(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(end),
              [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    const int left = count / 2;
    // The first chunks whose weight reaches the left ranks' share; each side keeps a chunk per rank.
    const double share = total * double(left) / double(count);
    std::size_t split = begin;
    for (double sum = 0.0; split < end && sum + 0.5 * weight[order[split]] < share; ++split)
      sum += weight[order[split]];
    split = std::clamp(split, begin + std::size_t(left), end - std::size_t(count - left));
    self(self, begin, split, first, left);
    self(self, split, end, first + left, count - left);
  };
  bisect(bisect, 0, chunks, 0, ranks);
  return rank_of;
}

}  // namespace exdyn::solver
