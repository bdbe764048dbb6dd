// The geometry of a contact pass from the deck's faces (contact_setup.cpp): its slave
// points and master segments, with their places in the whole pass, areas and lengths.
#pragma once

#include <limits>
#include <vector>

#include "contact/contact_pass.hpp"
#include "input/options.hpp"
#include "model/contact_setup.hpp"
#include "model/model.hpp"

namespace exdyn::solver {

struct PassGeometry {
  contact::ContactSurfaces surfaces;
  std::vector<double> area;  // node mode: tributary area of each slave node, m^2
  // quadrature mode: for each slave node, sum over the points of its segments of
  // |N_I| weight sum_J |N_J|, m^2: the area over which its springs act (the cap).
  std::vector<double> spring_area;
  double modulus = std::numeric_limits<double>::infinity();          // smallest M of the parts involved, Pa
  double smallest_length = std::numeric_limits<double>::infinity();  // m
  PassPlace place;                           // the points' and segments' places in the whole pass
  std::vector<std::size_t> master_face_end;  // where each master face's segments end
};

// A pass's slave points (nodes, Gauss points of its slave segments, or mortar's slave
// segments), master segments, edges and moving nodes, from the deck's faces.
// keep: the segments of the faces that count (none: all). whole_master false: no edges
// and no moving nodes (a single surface's faces after its first, whose master side is
// the first's).
PassGeometry pass_geometry(const input::Deck& deck, const Model& model, const input::ContactOptions& options,
                           const std::vector<input::FaceRef>& slave,
                           const std::vector<input::FaceRef>& master, const mesh::KeepSegment& keep = {},
                           bool whole_master = true);

// What the surface does past each edge of each master segment (edge_contact.hpp),
// counting only the segments `live` marks (empty: all; a surface that erosion changes).
std::vector<contact::SegmentEdges> segment_edges(const Model& model,
                                                 const std::vector<contact::SegmentNodes>& segments,
                                                 const std::vector<std::uint8_t>& live = {});
// The `continued` bits of `edges` (segment_edges') anew for `live`, their mirror axes
// kept: the edges of a surface that erosion changed.
void continue_edges(const std::vector<contact::SegmentNodes>& segments, const std::vector<std::uint8_t>& live,
                    std::vector<contact::SegmentEdges>& edges);

// Face f of the model, cut to the segments `keep` keeps (none: whole).
mesh::Face contact_face(const Model& model, const input::FaceRef& f, const mesh::KeepSegment& keep);

// The spring area of each of `nodes` (sorted) over `segments` (m^2): the sum over the
// n x n Gauss points of the segments at each node of |N_I| w sum_J |N_J|, n as
// points_per_side. What a node's springs act over, for the caps of penalty.hpp.
std::vector<double> spring_areas(const input::ContactOptions& options, const NodalVectors& x,
                                 const std::vector<contact::SegmentNodes>& segments,
                                 const std::vector<std::uint32_t>& nodes);

// The dilatational modulus lambda + 2 mu of part `part`'s material, Pa.
double dilatational_modulus(const input::Deck& deck, int part);

}  // namespace exdyn::solver
