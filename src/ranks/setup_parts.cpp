// Bytes between ranks and a scattered part's pieces (setup_parts.hpp).
#include "ranks/setup_parts.hpp"

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

namespace exdyn::solver::setup {

// Bytes from `from` to `to` (MPI_Send and MPI_Recv, pieces of at most 1 GiB): the
// sender's `bytes` become the receiver's.
void send_bytes(const mpi::Communicator& comm, int to, const std::vector<char>& bytes) {
  const std::uint64_t size = bytes.size();
  mpi::check(MPI_Send(&size, 1, MPI_UINT64_T, to, 0, comm.comm), "MPI_Send of a part's size");
  for (std::uint64_t at = 0; at < size; at += piece_bytes)
    mpi::check(MPI_Send(bytes.data() + at, int(std::min(piece_bytes, size - at)), MPI_CHAR, to, 0, comm.comm),
               "MPI_Send of a part");
}
std::vector<char> receive_bytes(const mpi::Communicator& comm, int from) {
  std::uint64_t size = 0;
  mpi::check(MPI_Recv(&size, 1, MPI_UINT64_T, from, 0, comm.comm, MPI_STATUS_IGNORE),
             "MPI_Recv of a part's size");
  std::vector<char> bytes(size);
  for (std::uint64_t at = 0; at < size; at += piece_bytes)
    mpi::check(MPI_Recv(bytes.data() + at, int(std::min(piece_bytes, size - at)), MPI_CHAR, from, 0,
                        comm.comm, MPI_STATUS_IGNORE),
               "MPI_Recv of a part");
  return bytes;
}
// Rank 0's bytes on every rank (MPI_Bcast in pieces of at most 1 GiB).
void broadcast_bytes(const mpi::Communicator& comm, std::vector<char>& bytes) {
  std::uint64_t size = bytes.size();
  mpi::check(MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm.comm), "MPI_Bcast of a size");
  bytes.resize(size);
  for (std::uint64_t at = 0; at < size; at += piece_bytes)
    mpi::check(MPI_Bcast(bytes.data() + at, int(std::min(piece_bytes, size - at)), MPI_CHAR, 0, comm.comm),
               "MPI_Bcast of a part");
}

// Runs `work` on rank 0 alone; an error it throws is every rank's: an InputError in
// its words (exit 2, as one process), any other error a runtime_error with its text.
// Collective over comm.
void on_rank_0(const mpi::Communicator& comm, const std::function<void()>& work) {
  std::vector<char> text;
  int status = 0;  // 0: done; 1: bad input; 2: another error
  if (comm.root()) {
    try {
      work();
    } catch (const InputError& e) {
      status = 1, text.assign(e.what(), e.what() + std::strlen(e.what()));
    } catch (const std::exception& e) {
      status = 2, text.assign(e.what(), e.what() + std::strlen(e.what()));
    }
  }
  mpi::check(MPI_Bcast(&status, 1, MPI_INT, 0, comm.comm), "MPI_Bcast of a status");
  if (status == 0) return;
  broadcast_bytes(comm, text);
  if (status == 1) throw InputError(std::string(text.begin(), text.end()));
  throw std::runtime_error(std::string(text.begin(), text.end()));
}

namespace {

// A rank's piece of a scattered part as it arrives from rank 0 (piece_for).
std::unique_ptr<PartPiece> receive_piece(SetupPart& part, const mpi::Communicator& comm) {
  const std::vector<char> bytes = receive_bytes(comm, 0);
  Unpacker in{bytes};
  auto piece = std::make_unique<PartPiece>();
  in.get(piece->elements);
  in.get(piece->connectivity);
  in.get(piece->nodes);
  in.get(piece->points);
  in.get(piece->around_nodes);
  in.get(piece->around_start);
  in.get(piece->around);
  piece->first_row = in.value<std::uint32_t>();
  in.get(piece->row_owner);
  auto figures = std::make_unique<mesh::Mesh>();
  figures->parts.push_back(SetupParts::unpack_range(in));
  part.built = std::move(figures);
  EXDYN_ASSERT(in.at == bytes.size());
  return piece;
}

// The sorted, unique entries of `values`.
void sort_unique(std::vector<std::uint32_t>& values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

// Rank r's piece of a part rank 0 holds whole (PartPiece): its elements, the nodes
// around them with the elements at those nodes, their coordinates and its output rows'
// owners.
PartPiece piece_for(const SetupParts& deck_parts, const SetupPart& part, const Chunks& chunks, int r,
                    int ranks) {
  const mesh::Mesh& whole = *part.built;
  const auto width = std::size_t(part.nodes_per_element);
  auto add_nodes = [&](std::uint32_t e, std::vector<std::uint32_t>& out) {
    out.insert(out.end(), whole.connectivity.begin() + std::ptrdiff_t(width * e),
               whole.connectivity.begin() + std::ptrdiff_t(width * (e + 1)));
  };
  PartPiece piece;
  std::vector<std::uint32_t> own;
  for (std::size_t c = 0; c < part.chunks; ++c)
    if (chunks.rank[part.first_chunk + c] == r)
      for (auto e = std::uint32_t(c * chunk_size);
           e < std::min<std::size_t>((c + 1) * chunk_size, part.element_count); ++e)
        own.push_back(e);
  for (const std::uint32_t e : own) add_nodes(e, piece.around_nodes);
  sort_unique(piece.around_nodes);
  piece.around_start.push_back(0);
  for (const std::uint32_t k : piece.around_nodes) {
    piece.around.insert(piece.around.end(), part.at_element.begin() + std::ptrdiff_t(part.at_start[k]),
                        part.at_element.begin() + std::ptrdiff_t(part.at_start[k + 1]));
    piece.around_start.push_back(std::uint32_t(piece.around.size()));
  }
  piece.elements = own;
  piece.elements.insert(piece.elements.end(), piece.around.begin(), piece.around.end());
  sort_unique(piece.elements);
  for (const std::uint32_t e : piece.elements) add_nodes(e, piece.connectivity);
  piece.nodes = piece.connectivity;
  sort_unique(piece.nodes);
  for (const std::uint32_t k : piece.nodes)
    for (int c = 0; c < 3; ++c) piece.points.push_back(whole.x_ref.component(c)[k]);
  // Rank r's output rows, [n r / p, n (r + 1) / p) of the n nodes (row_exchange),
  // within the part.
  const std::size_t n = deck_parts.nodes, p = std::size_t(ranks);
  const std::size_t begin = std::max<std::size_t>(n * std::size_t(r) / p, part.first_node),
                    end =
                        std::min<std::size_t>(n * std::size_t(r + 1) / p, part.first_node + part.node_count);
  piece.first_row = begin < end ? std::uint32_t(begin - part.first_node) : 0;
  for (std::size_t g = begin; g < end; ++g)
    piece.row_owner.push_back(owner_of_node(part, std::uint32_t(g), chunks));
  return piece;
}

}  // namespace

// Each rank's piece of each scattered part (PartPiece), sent by rank 0, which holds the
// part whole, for the chunks' ranks of `chunks`. Collective over comm.
void scatter_pieces(SetupParts& deck_parts, const Chunks& chunks, const mpi::Communicator& comm) {
  for (SetupPart& part : deck_parts.list) {
    if (!part.scattered) continue;
    if (!comm.root()) {
      part.piece = nullptr;
      part.piece = receive_piece(part, comm);
      continue;
    }
    for (int r = 1; r < comm.size; ++r) {
      const PartPiece piece = piece_for(deck_parts, part, chunks, r, comm.size);
      Packer out;
      out.put(piece.elements);
      out.put(piece.connectivity);
      out.put(piece.nodes);
      out.put(piece.points);
      out.put(piece.around_nodes);
      out.put(piece.around_start);
      out.put(piece.around);
      out.put_value(piece.first_row);
      out.put(piece.row_owner);
      // The part's faces cut to the segments with a node of rank r's elements.
      SetupParts::pack_range(part.built->parts[0], out, touching(piece.around_nodes));
      send_bytes(comm, r, out.bytes);
    }
  }
}

}  // namespace exdyn::solver::setup
