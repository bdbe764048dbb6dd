// A restart checkpoint on many ranks (docs/output.md, "Checkpoints"): the model's state
// in one process's numbering, in the file a run on one process writes. The large
// arrays are written by the ranks in pieces (the output's rows, the chunks), the rest
// gathered to rank 0; a restart on any number of ranks reads the file on every rank and
// takes its own nodes, elements and chunks from it. The nodes and
// elements by their global ids (the owners' values: every holder of a node has the
// same bits), the integration-point states chunk by chunk (a rank holds whole chunks,
// whose packs are those of the whole block), the contact in contact_checkpoint.hpp.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "common/errors.hpp"
#include "common/mpi.hpp"
#include "element/element_block.hpp"
#include "output/checkpoint_file.hpp"
#include "ranks/decomposition.hpp"

namespace exdyn::solver {

// Every rank's `values` on rank 0, rank after rank (elsewhere: empty). Collective.
template <class T>
std::vector<std::vector<T>> gather_to_root(const mpi::Communicator& comm, const std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  const int bytes = int(sizeof(T) * values.size());
  std::vector<int> counts(std::size_t(comm.size)), offsets(std::size_t(comm.size), 0);
  mpi::check(MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm.comm),
             "MPI_Gather of a checkpoint's counts");
  for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<T> all(comm.root() ? std::size_t(offsets.back() + counts.back()) / sizeof(T) : 0);
  mpi::check(MPI_Gatherv(values.data(), bytes, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                         0, comm.comm),
             "MPI_Gatherv of a checkpoint's values");
  std::vector<std::vector<T>> from;
  if (!comm.root()) return from;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    const auto first = all.begin() + offsets[r] / std::ptrdiff_t(sizeof(T));
    from.emplace_back(first, first + counts[r] / std::ptrdiff_t(sizeof(T)));
  }
  return from;
}

// The rows (k values each) of `local` at the items `which` (local ids) as the whole's
// rows `global` of `rows`, on rank 0 (elsewhere: empty). `local` empty on every rank:
// empty. Collective.
template <class T>
std::vector<T> gather_rows(const mpi::Communicator& comm, const std::vector<T>& local,
                           const std::vector<std::uint32_t>& which, const std::vector<std::uint32_t>& global,
                           std::size_t items, std::size_t rows) {
  const std::size_t k = items == 0 ? 0 : local.size() / items;
  EXDYN_ASSERT(k * items == local.size());
  std::vector<std::uint32_t> ids;
  std::vector<T> values;
  for (const std::uint32_t i : which) {
    ids.push_back(global[i]);
    values.insert(values.end(), local.begin() + std::ptrdiff_t(k * i),
                  local.begin() + std::ptrdiff_t(k * (i + 1)));
  }
  const auto all_ids = gather_to_root(comm, ids);
  const auto all = gather_to_root(comm, values);
  std::vector<T> whole;
  if (!comm.root()) return whole;
  std::size_t total = 0;
  for (const auto& from : all) total += from.size();
  if (total == 0) return whole;
  const std::size_t width = total / rows;
  EXDYN_ASSERT(width * rows == total);
  whole.resize(total);
  for (std::size_t r = 0; r < all.size(); ++r)
    for (std::size_t j = 0; j < all_ids[r].size(); ++j)
      std::copy(all[r].begin() + std::ptrdiff_t(width * j), all[r].begin() + std::ptrdiff_t(width * (j + 1)),
                whole.begin() + std::ptrdiff_t(width * all_ids[r][j]));
  return whole;
}

// The rows `global` (of this rank's items) of `whole` (its rows k values each) into `local`.
template <class T>
void pick_rows(const std::vector<T>& whole, const std::vector<std::uint32_t>& global, std::size_t rows,
               std::vector<T>& local, const char* what) {
  if (whole.empty() && local.empty()) return;
  const std::size_t k = rows == 0 ? 0 : whole.size() / rows;
  if (k * rows != whole.size() || (!local.empty() && local.size() != k * global.size()))
    throw InputError(std::string("the checkpoint's ") + what + " is of another model");
  local.resize(k * global.size());
  for (std::size_t i = 0; i < global.size(); ++i)
    std::copy(whole.begin() + std::ptrdiff_t(k * global[i]),
              whole.begin() + std::ptrdiff_t(k * (global[i] + 1)), local.begin() + std::ptrdiff_t(k * i));
}

// The owned nodes of this rank (local ids), and all its elements.
std::vector<std::uint32_t> owned_nodes(const Decomposition& d);
std::vector<std::uint32_t> all_items(std::size_t count);

// The whole model's blocks' scalars (ElementBlock::material_state's committed and dt,
// failure.any_not_alive) on rank 0. Collective.
std::vector<element::ElementBlock> gather_block_scalars(const Decomposition& d, const Model& model);

// This rank's chunks of each block's point states, damage and erosion as pieces of the
// whole block's sections (NAME#CHUNK, checkpoint_file.hpp), and the names of every
// block's sections so written (the same on every rank).
void add_block_pieces(output::CheckpointWriter& file, const Decomposition& d, const Model& model,
                      std::set<std::string>& pieced);

// This rank's blocks' point states, damage and erosion from the whole blocks'.
void pick_blocks(const Decomposition& d, const std::vector<element::ElementBlock>& whole, Model& model);

}  // namespace exdyn::solver
