// The choice of a slave point's contact from its candidates' projections
// (docs/contact.md, "Local search and the choice of segment"): the closest projection
// that converged to a minimum inside its segment; a point at an edge or corner shared by
// several segments takes that shared point along their mean normal, whichever segment
// the tie goes to; a point with a nearer candidate plane outside its segment lets the
// edge points decide (edge_contact.hpp: the dead zone of a fold, a valley, a face's
// boundary).
#pragma once

#include <cstddef>

#include "common/nodal_vectors.hpp"
#include "contact/contact_pass.hpp"

namespace exdyn::contact {

// On a single surface: whether point p may touch the segments of its candidates, each
// into state.admitted (the facing rule of single_surface.hpp).
void admit_candidates(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                      ContactPassState& state, std::size_t p, const NodalVectors& x_ref,
                      const NodalVectors& u);

// Whether candidate pair c may touch: always, but on a single surface only where the
// point and the segment face each other (admit_candidates).
inline bool admitted(const ContactSurfaces& surfaces, const ContactPassState& state, std::size_t c) {
  return !surfaces.single_surface || state.admitted[c] != 0;
}

// Whether a projection counts as a contact where it is: a converged minimum inside its
// segment, or within own_segment_reach of a mortar piece's own segment.
bool counts_inside(const ContactSurfaces& surfaces, const ProjectionResult& r);

// Slave point p's contact from the projections of its candidates (state.results) into
// state.contacts[p]: segment -1 when it has none.
void choose_contact(const ContactSurfaces& surfaces, ContactPassState& state, std::size_t p,
                    const NodalVectors& x_ref, const NodalVectors& u);

// The unit vector along the sum of `count` vectors, summed in an order of their values
// alone (each component by increasing magnitude), so that the same vectors give the
// same bits in any order and their mirror images the mirror image; zero when they
// cancel.
Vec3 mean_direction(const Vec3* vectors, std::size_t count);

}  // namespace exdyn::contact
