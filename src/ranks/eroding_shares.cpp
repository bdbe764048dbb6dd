// Contact on the faces erosion opens, on many ranks (distributed_contact.hpp,
// open_eroded_shares; docs/parallel.md, "Contact across ranks").
//
// Every rank holds such a surface's whole pass (PassShare::whole), built as one process
// builds it. When an element fails anywhere, the ranks gather the failed elements and
// each brings the whole pass to them (follow_life: the same segments, points, edges
// and edge neighbours as one process), then its own segments' edges and neighbours
// from it. Every rank then searches that pass again in the same step (the ghost
// segments travel with their new edges), and each view takes its segments' and points'
// life from the whole pass: the same candidates, forces and bits as one process.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "common/errors.hpp"
#include "element/element_block.hpp"
#include "model/opened_faces.hpp"
#include "ranks/contact_share.hpp"
#include "ranks/distributed_contact.hpp"

namespace exdyn::solver {

namespace shares {

void apply_life(PassShare& share) {
  const contact::ContactSurfaces& whole = share.whole;
  contact::ContactSurfaces& view = share.view;
  const std::size_t segments = share.known.size();
  view.segment_live.resize(segments);
  view.segment_element.resize(segments);
  view.segment_across.resize(segments);
  for (std::size_t k = 0; k < segments; ++k) {
    const std::uint32_t id = share.known[k];
    view.segment_live[k] = whole.segment_live[id];
    view.segment_element[k] = whole.segment_element[id];
    view.segment_across[k] = whole.segment_across[id];
  }
  EXDYN_ASSERT(share.whole_point.size() == view.point_count());
  view.point_live.resize(share.whole_point.size());
  for (std::size_t p = 0; p < share.whole_point.size(); ++p)
    view.point_live[p] = whole.point_live[share.whole_point[p]];
}

}  // namespace shares

void open_eroded_shares(ContactModel& contact, DistributedContact& dc, const Model& model,
                        const std::vector<std::uint32_t>& global_element, std::size_t global_elements) {
  if (std::none_of(dc.passes.begin(), dc.passes.end(),
                   [](const PassShare& share) { return !share.whole.segment_element.empty(); }))
    return;                           // the same on every rank
  std::vector<std::uint32_t> failed;  // this rank's elements gone, then every rank's
  for (const element::ElementBlock& block : model.blocks) {
    const std::vector<std::uint8_t>& status = block.failure.status;
    for (std::size_t e = 0; e < status.size(); ++e)
      if (status[e] != std::uint8_t(element::ElementStatus::alive))
        failed.push_back(global_element.empty() ? std::uint32_t(block.first_element + e)
                                                : global_element[block.first_element + e]);
  }
  {
    const ScopedTimer timer(dc.wait_seconds);
    failed = mpi::all_gather_varying(dc.comm, failed);
  }
  std::vector<std::uint8_t> alive(global_elements, 1);
  for (const std::uint32_t e : failed) alive[e] = 0;
  std::size_t k = 0;
  for (ContactPair& pair : contact.pairs)
    for (std::size_t p = 0; p < pair.passes.size(); ++p, ++k) {
      PassShare& share = dc.passes[k];
      contact::ContactSurfaces& whole = share.whole;
      if (whole.segment_element.empty() || !follow_life(alive, whole)) continue;
      contact::ContactSurfaces& own = share.own;
      for (std::size_t i = 0; i < own.segments.size(); ++i) {  // what its ghosts carry to the others
        const std::uint32_t id = share.segment_ids[i];
        if (!own.edges.empty()) own.edges[i] = whole.edges[id];
        if (own.single_surface) own.edge_neighbours[i] = whole.edge_neighbours[id];
      }
      for (contact::Anchor& anchor : pair.states[p].anchors)  // friction anchors on segments gone
        if (anchor.segment >= 0 && whole.segment_live[share.known[std::size_t(anchor.segment)]] == 0)
          anchor = contact::Anchor{};
      share.opened = true;
    }
}

}  // namespace exdyn::solver
