#include "model/opened_faces.hpp"

#include <algorithm>

#include "element/element_block.hpp"
#include "mesh/interior_faces.hpp"
#include "model/contact_geometry.hpp"
#include "model/single_surface_setup.hpp"

namespace exdyn::solver {

bool part_can_fail(const Model& model, int part) {
  return std::size_t(part) < model.blocks.size() && model.blocks[std::size_t(part)].law.failure.active();
}

std::vector<input::FaceRef> opening_faces(const Model& model, const std::vector<input::FaceRef>& faces) {
  std::vector<int> parts;
  for (const input::FaceRef& f : faces)
    if (part_can_fail(model, f.part) && std::find(parts.begin(), parts.end(), f.part) == parts.end())
      parts.push_back(f.part);
  std::vector<input::FaceRef> opening;
  for (const int part : parts) {
    const std::vector<mesh::Face>& interior = model.mesh.parts[std::size_t(part)].interior_faces;
    for (std::size_t local_face = 0; local_face < interior.size(); ++local_face)
      if (!interior[local_face].segments.empty())
        opening.push_back(input::FaceRef{part, input::PartFace::interior, int(local_face)});
  }
  return opening;
}

namespace {

// Each element's life now: 1 alive (or on a part that cannot fail), 0 gone.
std::vector<std::uint8_t> elements_alive(const Model& model) {
  std::vector<std::uint8_t> alive(model.mesh.element_count(), 1);
  for (const element::ElementBlock& block : model.blocks) {
    const std::vector<std::uint8_t>& status = block.failure.status;
    for (std::size_t e = 0; e < status.size(); ++e)
      alive[block.first_element + e] = status[e] == std::uint8_t(element::ElementStatus::alive);
  }
  return alive;
}

// Each segment's four edges numbered (ContactSurfaces::edge_ids).
std::vector<std::uint32_t> number_edges(const std::vector<contact::SegmentNodes>& segments) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys;  // (edge's corner nodes, 4 segment + edge)
  keys.reserve(4 * segments.size());
  for (std::size_t k = 0; k < segments.size(); ++k)
    for (int e = 0; e < 4; ++e) {
      const std::uint32_t a = segments[k].nodes[contact::edge_corners[e][0]],
                          b = segments[k].nodes[contact::edge_corners[e][1]];
      keys.emplace_back(std::uint64_t(std::min(a, b)) << 32 | std::max(a, b), std::uint32_t(4 * k + e));
    }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> ids(keys.size());
  std::uint32_t id = 0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i > 0 && keys[i].first != keys[i - 1].first) ++id;
    ids[keys[i].second] = id;
  }
  return ids;
}

// The edges' `continued` bits (their mirror axes kept) and the edge neighbours of `s`
// over its live segments: those of continue_edges and edge_neighbours, counted by edge
// number (ContactSurfaces::edge_ids) instead of by a map of node pairs.
void follow_edges(contact::ContactSurfaces& s) {
  const std::size_t edges =
      s.edge_ids.empty() ? 0 : 1 + *std::max_element(s.edge_ids.begin(), s.edge_ids.end());
  std::vector<std::uint32_t> count(edges, 0);
  std::vector<std::int32_t> first(edges, -1), second(edges, -1);  // the lowest two live segments at it
  for (std::size_t k = 0; k < s.segments.size(); ++k)
    if (s.segment_live[k] != 0)
      for (std::size_t e = 0; e < 4; ++e) {
        const std::uint32_t id = s.edge_ids[4 * k + e];
        if (count[id] == 0)
          first[id] = std::int32_t(k);
        else if (count[id] == 1)
          second[id] = std::int32_t(k);
        ++count[id];
      }
  s.edge_neighbours.resize(s.segments.size());
  for (std::size_t k = 0; k < s.segments.size(); ++k) {
    s.edges[k].continued = 0;
    for (std::size_t e = 0; e < 4; ++e) {
      const std::uint32_t id = s.edge_ids[4 * k + e];
      if (count[id] > 1 || s.edges[k].mirror_axis[e] >= 0)
        s.edges[k].continued |= static_cast<std::uint8_t>(1u << e);
      s.edge_neighbours[k][e] = count[id] == 1   ? -1
                                : count[id] == 2 ? (first[id] == std::int32_t(k) ? second[id] : first[id])
                                                 : -2;
    }
  }
}

}  // namespace

void find_segment_elements(const Model& model, contact::ContactSurfaces& s) {
  std::vector<mesh::BrickFace> faces;  // of every part that can fail, sorted
  for (std::size_t part = 0; part < model.mesh.parts.size(); ++part)
    if (part_can_fail(model, int(part))) {
      const std::vector<mesh::BrickFace> own = mesh::part_brick_faces(model.mesh, int(part));
      faces.insert(faces.end(), own.begin(), own.end());
    }
  if (faces.empty()) return;
  auto by_corners = [](const mesh::BrickFace& a, const mesh::BrickFace& b) { return a.corners < b.corners; };
  std::sort(faces.begin(), faces.end(), [](const mesh::BrickFace& a, const mesh::BrickFace& b) {
    return a.corners != b.corners ? a.corners < b.corners : a.where < b.where;
  });
  s.segment_element.assign(s.segments.size(), contact::no_element);
  s.segment_across.assign(s.segments.size(), contact::no_element);
  bool any = false;
  for (std::size_t k = 0; k < s.segments.size(); ++k) {
    mesh::BrickFace key{};
    std::copy_n(s.segments[k].nodes.begin(), 4, key.corners.begin());
    std::sort(key.corners.begin(), key.corners.end());
    const auto [first, last] = std::equal_range(faces.begin(), faces.end(), key, by_corners);
    for (auto f = first; f != last; ++f) {
      const auto element = std::uint32_t(f->where / 6);
      if (mesh::outward_of(model.mesh, f->where, s.segments[k].nodes.data()))
        s.segment_element[k] = element, any = true;
      else
        s.segment_across[k] = element;
    }
  }
  if (!any) {
    s.segment_element.clear(), s.segment_across.clear();
    return;
  }
  s.edges = segment_edges(model, s.segments);  // their mirror axes; follow_life counts the live ones
  s.edge_ids = number_edges(s.segments);
  follow_life(elements_alive(model), s);
}

bool follow_life(const std::vector<std::uint8_t>& alive, contact::ContactSurfaces& s) {
  auto on = [&](std::uint32_t element) { return element != contact::no_element && alive[element] != 0; };
  std::vector<std::uint8_t> live(s.segments.size());
  for (std::size_t k = 0; k < live.size(); ++k)
    live[k] = std::uint8_t((s.segment_element[k] == contact::no_element || on(s.segment_element[k])) &&
                           !on(s.segment_across[k]));
  if (live == s.segment_live) return false;
  s.segment_live = std::move(live);
  s.point_live.assign(s.point_count(), 0);
  if (s.quadrature) {  // a Gauss point's slave segment k is master segment k
    for (std::size_t p = 0; p < s.point_live.size(); ++p)
      s.point_live[p] = s.segment_live[s.quadrature_points[p].segment];
  } else {
    for (std::size_t p = 0; p < s.point_live.size(); ++p)
      for (std::uint32_t k = s.corner_begin[p]; k < s.corner_begin[p + 1]; ++k)
        s.point_live[p] = std::uint8_t(s.point_live[p] | s.segment_live[s.node_corners[k].segment]);
  }
  follow_edges(s);
  return true;
}

int open_eroded_faces(ContactModel& contact, const Model& model) {
  if (!follows_erosion(contact)) return 0;
  const std::vector<std::uint8_t> alive = elements_alive(model);
  int changed = 0;
  for (ContactPair& pair : contact.pairs)
    for (std::size_t p = 0; p < pair.passes.size(); ++p) {
      contact::ContactSurfaces& s = pair.passes[p];
      if (s.segment_element.empty() || !follow_life(alive, s)) continue;
      contact::ContactPassState& state = pair.states[p];
      state.built = false;
      for (contact::Anchor& anchor : state.anchors)
        if (anchor.segment >= 0 && !s.segment_on(std::size_t(anchor.segment))) anchor = contact::Anchor{};
      ++changed;
    }
  return changed;
}

bool follows_erosion(const ContactModel& contact) {
  for (const ContactPair& pair : contact.pairs)
    for (const contact::ContactSurfaces& s : pair.passes)
      if (!s.segment_element.empty()) return true;
  return false;
}

}  // namespace exdyn::solver
