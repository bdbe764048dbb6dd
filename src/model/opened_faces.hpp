// Contact on the faces that erosion opens (docs/contact.md, "Faces that erosion opens").
// A single surface `surface: all` over a part that can fail holds, besides the part's
// exterior, every face its bricks share, twice: once outward of either brick
// (mesh/interior_faces.hpp). A segment is on the body's boundary while its brick lives
// and the brick across it (if any) has eroded; a slave point while it lies on such a
// segment. When an element erodes, the segments and points follow at the next step,
// with the surface's edges, and every pass over them searches again: a face exposed at
// step n takes part in the contact from step n on, the eroded element's faces no more.
#pragma once

#include <vector>

#include "contact/contact_pass.hpp"
#include "input/options.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"

namespace exdyn::solver {

// Whether part `part`'s elements can fail (its material has a failure model).
bool part_can_fail(const Model& model, int part);

// The faces erosion can open under `faces` (a single surface's): the interior faces of
// each part among them that can fail, by the bricks' local face, those with segments
// (build_model keeps them: mesh::PartRange::interior_faces).
std::vector<input::FaceRef> opening_faces(const Model& model, const std::vector<input::FaceRef>& faces);

// Each segment's element and the element across it (ContactSurfaces::segment_element),
// and the segments and points on the boundary of the model as built (every element
// alive). Leaves `s` as it is when none of its segments lies on a part that can fail.
void find_segment_elements(const Model& model, contact::ContactSurfaces& s);

// Brings the segments and points of `s` (segment_element not empty) to the elements'
// life `alive` (1 alive, 0 gone; by the element ids of segment_element), with the
// edges' `continued` bits (their mirror axes kept) and the edge neighbours; whether
// they changed.
bool follow_life(const std::vector<std::uint8_t>& alive, contact::ContactSurfaces& s);

// Brings every eroding surface to the elements' status now (an element is gone once it
// is not alive: failed at an earlier step, element_block.hpp): its segments and points,
// its edges and edge neighbours; a pass whose surface changed searches again (its
// friction anchors on segments gone start over). Returns the number of passes changed.
int open_eroded_faces(ContactModel& contact, const Model& model);

// Whether any pass follows erosion.
bool follows_erosion(const ContactModel& contact);

}  // namespace exdyn::solver
