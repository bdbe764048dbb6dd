// What a checkpoint holds of the model's state (docs/output.md, "Checkpoints"): every
// value a step reads that an earlier step wrote. One list per object, walked by a
// saver (to a checkpoint) and by a loader (from one), so the two cannot disagree.
// A value is saved as it is in memory (the point states in the packs of the element
// kernels' instruction set: a restart runs the same set, checkpoint.cpp).
#pragma once

#include <array>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"
#include "output/checkpoint_file.hpp"
#include "solver/step_passes.hpp"

namespace exdyn::solver {

// Writes each value as a section named by its path, but those the ranks write in pieces
// (`pieced`, on many ranks: checkpoint_ranks.hpp).
struct StateSaver {
  output::CheckpointWriter& file;
  const std::set<std::string>* pieced = nullptr;

  bool whole(const std::string& name) const { return pieced == nullptr || pieced->count(name) == 0; }
  template <class T>
  void operator()(const std::string& name, const std::vector<T>& values) {
    if (whole(name)) file.add(name, values);
  }
  void operator()(const std::string& name, const NodalVectors& v) {
    for (int c = 0; c < 3; ++c)
      if (whole(name + "." + char('x' + c))) file.add(name + "." + char('x' + c), v.component(c));
  }
  template <class T, std::size_t N>
  void operator()(const std::string& name, const std::array<std::vector<T>, N>& arrays) {
    for (std::size_t k = 0; k < N; ++k) (*this)(name + "[" + std::to_string(k) + "]", arrays[k]);
  }
  template <class T, class = std::enable_if_t<std::is_trivially_copyable_v<T>>>
  void operator()(const std::string& name, const T& value) {
    if (whole(name)) file.add_value(name, value);
  }
};

// Reads each value back. A vector of the size it has is read into its own storage
// (the element blocks keep pointers into some); nodal vectors must have the model's size.
struct StateLoader {
  const output::CheckpointReader& file;

  template <class T>
  void operator()(const std::string& name, std::vector<T>& values) const {
    std::vector<T> read = file.values<T>(name);
    if (read.size() == values.size())
      std::copy(read.begin(), read.end(), values.begin());
    else
      values = std::move(read);
  }
  void operator()(const std::string& name, NodalVectors& v) const {
    const long size = v.size() > 0 ? long(v.size()) : -1;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> read = file.values<double>(name + "." + char('x' + c), size);
      if (size < 0)
        v.component(c) = std::move(read);
      else
        std::copy(read.begin(), read.end(), v.component(c).begin());
    }
  }
  template <class T, std::size_t N>
  void operator()(const std::string& name, std::array<std::vector<T>, N>& arrays) const {
    for (std::size_t k = 0; k < N; ++k) (*this)(name + "[" + std::to_string(k) + "]", arrays[k]);
  }
  template <class T, class = std::enable_if_t<std::is_trivially_copyable_v<T>>>
  void operator()(const std::string& name, T& value) const {
    value = file.value<T>(name);
  }
};

// The point states, damage and erosion of every block.
template <class Archive>
void visit_blocks(Archive& archive, const std::vector<element::ElementBlock>& blocks);
// The pairs' and walls' search, friction and erosion state and their run figures, each
// pass in one process's numbering (its slave points by ascending key, its segments by
// their index in the whole pass). keys: each pair pass's point keys (distributed_contact.hpp),
// given to save a pass made for the file on many ranks and read back; without, they
// are the surfaces' own.
template <class Archive>
void visit_contact(Archive& archive, ContactModel& contact,
                   std::vector<std::vector<std::uint64_t>>* keys = nullptr);
// The nodal fields, element fields and accumulators of the time loop's State; the
// contact's arrays at contact_nodes only (ContactModel::nodes, ascending global ids,
// saved with them; `rows`: each one's place in the arrays, where not its id: a whole
// state made for the file on many ranks holds them compact). Loading, an empty
// contact_nodes takes the saved ones (its arrays the whole model's size).
template <class Archive>
void visit_state(Archive& archive, State& state, std::vector<std::uint32_t>& contact_nodes,
                 const std::vector<std::uint32_t>* rows = nullptr);
// After loading: what a pass's last search set beside its saved state (a mortar pass's
// view of its segments).
void finish_loading_contact(ContactModel& contact);

}  // namespace exdyn::solver
