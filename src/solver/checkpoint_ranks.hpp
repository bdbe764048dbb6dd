// A restart checkpoint on many ranks (docs/output.md, "Checkpoints"): the state in one
// process's numbering, in the file a run on one process writes: the nodal and element
// arrays and the point states written by the ranks in pieces, the rest made on rank 0;
// and each rank's part taken from it on a restart on any number of ranks
// (ranks/rank_checkpoint.hpp, ranks/contact_checkpoint.hpp).
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "output/checkpoint_file.hpp"
#include "ranks/decomposition.hpp"
#include "solver/step_passes.hpp"

namespace exdyn::solver {

// What checkpoint_state.hpp's visitors walk, for the whole model.
struct WholeState {
  State state;
  std::vector<std::uint32_t> contact_nodes;  // global ids, ascending
  std::vector<std::uint32_t> contact_rows;   // each one's row in the contact arrays (saving: compact)
  std::vector<element::ElementBlock> blocks;
  ContactModel contact;
  std::vector<std::vector<std::uint64_t>> keys;  // each pass's point keys
};

// This rank's output rows of the state's nodal and element arrays as pieces of their
// sections (NAME#RANK, checkpoint_file.hpp), and the names of the sections so written
// (the same on every rank). Collective over d.comm.
void add_state_pieces(output::CheckpointWriter& file, const State& state, Decomposition& d,
                      std::set<std::string>& pieced);

// The rest of the whole state on rank 0 (elsewhere: unset; the arrays written in
// pieces left empty). Collective over d.comm.
WholeState gather_whole_state(const State& state, const Model& model, Decomposition& d,
                              const ContactModel& contact);

// This rank's state from a checkpoint (every rank reads it). Collective over d.comm.
void load_whole_state(const output::CheckpointReader& file, State& state, Model& model, Decomposition& d,
                      ContactModel& contact);

// A hash of the whole mesh (each element's global id, its nodes' global ids and
// reference coordinates), the same on any number of ranks: each element's hash is
// added (mod 2^64: in any order) over the ranks. Collective over d.comm.
std::uint64_t whole_mesh_hash(const Model& model, const Decomposition& d);

}  // namespace exdyn::solver
