// The model's state in a checkpoint on many ranks (rank_checkpoint.hpp): the element
// blocks' states chunk by chunk.
#include "ranks/rank_checkpoint.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <set>
#include <string>

#include "common/isa.hpp"
#include "element/element_isa.hpp"

namespace exdyn::solver {

namespace {

// Each saved array of a block's states, with its section's name (checkpoint_state.cpp's
// visit_blocks) and whether it is interleaved in packs of the ISA's lanes (else: the
// same number of values for each element).
template <class State, class Failure, class F>
void for_each_array(State& m, Failure& f, F&& visit) {
  visit("points[0]", m.points[0], true);
  visit("points[1]", m.points[1], true);
  visit("hourglass[0]", m.hourglass[0], true);
  visit("hourglass[1]", m.hourglass[1], true);
  visit("plastic_strain", m.plastic_strain, false);
  visit("status", f.status, false);
  visit("damage", f.damage, false);
  visit("failure_plastic_strain", f.plastic_strain, false);
  visit("distorted", f.distorted, false);
  visit("held", f.held, false);
}

// The values [begin, end) of an array of `size` values over `count` elements that
// hold elements [first, last).
std::pair<std::size_t, std::size_t> range_of(std::size_t size, std::size_t count, bool packed,
                                             std::size_t first, std::size_t last) {
  const auto lanes = std::size_t(element::lanes_for(selected_isa()));
  if (!packed) {
    const std::size_t per = size / count;
    EXDYN_ASSERT(per * count == size);
    return {first * per, last * per};
  }
  const std::size_t packs = (count + lanes - 1) / lanes, per = size / packs;
  EXDYN_ASSERT(per * packs == size && first % lanes == 0);
  return {first / lanes * per, (last + lanes - 1) / lanes * per};
}

// The global block of local block b, and the global chunk of its chunk k.
std::size_t global_block(const Model& model, const element::ElementBlock& block) {
  return std::size_t(model.mesh.element_part[block.first_element]);
}
std::size_t global_chunk(const Decomposition& d, const element::ElementBlock& block, std::size_t gb,
                         std::size_t k) {
  const std::uint32_t g = d.global_element[block.first_element + block.chunk_begin[k]];
  return (g - d.block_first_element[gb]) / element::element_chunk;
}

}  // namespace

std::vector<std::uint32_t> owned_nodes(const Decomposition& d) {
  std::vector<std::uint32_t> nodes;
  for (std::size_t i = 0; i < d.owned.size(); ++i)
    if (d.owned[i] != 0) nodes.push_back(std::uint32_t(i));
  return nodes;
}

std::vector<std::uint32_t> all_items(std::size_t count) {
  std::vector<std::uint32_t> items(count);
  for (std::size_t i = 0; i < count; ++i) items[i] = std::uint32_t(i);
  return items;
}

std::vector<element::ElementBlock> gather_block_scalars(const Decomposition& d, const Model& model) {
  const std::size_t blocks = d.block_first_element.size();
  std::vector<element::ElementBlock> whole(d.comm.root() ? blocks : 0);
  for (std::size_t gb = 0; gb < blocks; ++gb) {
    const element::ElementBlock* mine = nullptr;
    for (const element::ElementBlock& block : model.blocks)
      if (global_block(model, block) == gb) mine = &block;
    // From the ranks holding the block: which array is committed, the strain
    // increment's step, whether an element is gone.
    std::vector<double> scalars;
    if (mine != nullptr)
      scalars = {double(mine->material_state.committed), mine->material_state.dt,
                 mine->failure.any_not_alive ? 1.0 : 0.0};
    const auto all = gather_to_root(d.comm, scalars);
    if (!d.comm.root()) continue;
    element::ElementBlock& w = whole[gb];
    bool first = true;
    for (const auto& from : all) {
      if (from.empty()) continue;
      if (first) w.material_state.committed = int(from[0]), w.material_state.dt = from[1];
      w.failure.any_not_alive = w.failure.any_not_alive || from[2] != 0.0;
      first = false;
    }
  }
  return whole;
}

void add_block_pieces(output::CheckpointWriter& file, const Decomposition& d, const Model& model,
                      std::set<std::string>& pieced) {
  element::ElementBlock names;
  for (std::size_t gb = 0; gb < d.block_first_element.size(); ++gb)
    for_each_array(names.material_state, names.failure, [&](const char* name, const auto&, bool) {
      pieced.insert("block" + std::to_string(gb) + "/" + name);
    });
  for (const element::ElementBlock& block : model.blocks) {
    const std::size_t gb = global_block(model, block);
    const std::string prefix = "block" + std::to_string(gb) + "/";
    for_each_array(
        block.material_state, block.failure, [&](const char* name, const auto& local, bool packed) {
          using T = typename std::decay_t<decltype(local)>::value_type;
          for (std::size_t k = 0; k + 1 < block.chunk_begin.size(); ++k) {
            const std::string piece = prefix + name + "#" + std::to_string(global_chunk(d, block, gb, k));
            if (local.empty()) {
              file.add(piece, nullptr, 0);
              continue;
            }
            const auto [begin, end] =
                range_of(local.size(), block.count, packed, block.chunk_begin[k], block.chunk_begin[k + 1]);
            file.add_view(piece, local.data() + begin, (end - begin) * sizeof(T));
          }
        });
  }
}

void pick_blocks(const Decomposition& d, const std::vector<element::ElementBlock>& whole, Model& model) {
  if (whole.size() != d.block_first_element.size())
    throw InputError("the checkpoint's element blocks are of another model");
  for (element::ElementBlock& block : model.blocks) {
    const std::size_t gb = global_block(model, block);
    element::ElementBlock& w = const_cast<element::ElementBlock&>(whole[gb]);
    const std::size_t count = d.block_elements[gb];
    block.material_state.committed = w.material_state.committed;
    block.material_state.dt = w.material_state.dt;
    std::vector<const void*> sources;
    for_each_array(w.material_state, w.failure,
                   [&](const char*, auto& source, bool) { sources.push_back(&source); });
    std::size_t index = 0;
    for_each_array(block.material_state, block.failure, [&](const char*, auto& local, bool packed) {
      using V = std::decay_t<decltype(local)>;
      const V& source = *static_cast<const V*>(sources[index++]);
      if (local.empty() && source.empty()) return;
      if (local.empty() != source.empty())
        throw InputError("the checkpoint's element states are of another model");
      for (std::size_t k = 0; k + 1 < block.chunk_begin.size(); ++k) {
        const std::size_t c = global_chunk(d, block, gb, k);
        const std::size_t first = c * element::element_chunk,
                          last = std::min(first + element::element_chunk, count);
        const auto [from, to] = range_of(source.size(), count, packed, first, last);
        const auto [begin, end] =
            range_of(local.size(), block.count, packed, block.chunk_begin[k], block.chunk_begin[k + 1]);
        if (to - from != end - begin)
          throw InputError("the checkpoint's element states are of another model");
        std::copy(source.begin() + std::ptrdiff_t(from), source.begin() + std::ptrdiff_t(to),
                  local.begin() + std::ptrdiff_t(begin));
      }
    });
    block.failure.any_not_alive =
        std::any_of(block.failure.status.begin(), block.failure.status.end(),
                    [](std::uint8_t s) { return s != std::uint8_t(element::ElementStatus::alive); });
  }
}

}  // namespace exdyn::solver
