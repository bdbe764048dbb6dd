// A mortar pass (slave_points: mortar; docs/contact.md, "Mortar"): segment to segment.
// Each step:
//   global search: candidate (slave segment, master segment) pairs from the bucket grid,
//     the slave segments' centres against the master boxes inflated by the capture
//     distance and the largest slave segment's extent (again only when nodes have moved
//     half the margin);
//   segmentation: each candidate pair cut into pieces, with the points of the triangle
//     rule on each (mortar.hpp);
//   then the points run as a pass of quadrature points (contact_pass.hpp): each is
//   projected onto its piece's master segment by the deck's method and carries the
//   penalty kappa w (-g) of its weight w, with a dashpot on the reduced mass per area of
//   its two segments, so that a uniform gap and approach give a uniform traction.
#pragma once

#include "contact/contact_pass.hpp"

namespace exdyn::contact {

// The segments of a mortar pass's view of its points (MortarState::view), set at each
// search; a restart sets them again from the pass's surfaces (solver/checkpoint.cpp).
void set_mortar_view_segments(const ContactSurfaces& surfaces, MortarState& mortar);

// As run_contact_pass, for surfaces.mortar (which run_contact_pass hands over to it).
// With records, (*records->point_keys)[s] is slave segment s's index in the whole pass;
// a point's key is that index times 2^14 plus its place among the segment's points.
void run_mortar_pass(const ContactSurfaces& surfaces, const ContactPassSettings& settings,
                     ContactPassState& state, const NodalVectors& x_ref, const NodalVectors& u,
                     const NodalVectors& v, const std::vector<double>& mass, NodalVectors& force,
                     std::vector<double>& gap, ContactStatistics& statistics, ContactPhaseSeconds& seconds,
                     RecordSink* records, bool search_when_moved);

// The most points of one slave segment a record key can tell apart.
inline constexpr int mortar_key_bits = 14;

}  // namespace exdyn::contact
