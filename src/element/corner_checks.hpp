// The passes over the corners of a block's current configuration x = x_ref + u: its
// stable time step and its inversion check. Both read the same 8 corners of every
// element, so the time loop runs them as one pass when both fall on a step
// (check_corners), and the element pass of a block whose loop can runs them on the
// corners it gathers, with no pass of their own (request_corner_checks, below). The
// chunks of the block run on the threads and are reduced in chunk order: the same
// result on any number of threads.
#pragma once

#include <cstdint>

#include "common/nodal_vectors.hpp"
#include "element/element_block.hpp"

namespace exdyn::element {

// The stable step of the block's current configuration without the Courant factor, s:
// min over elements of L_e(x) / c1 (8 corners: L_e = V / the largest face's area, V by
// the 2 x 2 x 2 Gauss rule) times block.step_scale, and the element (global index) that
// sets it (the lowest of equal ones).
CurrentStep current_time_step(const ElementBlock& block, const NodalVectors& x_ref, const NodalVectors& u);

// The lowest-indexed element of [element_begin, element_end) (local indices) with a
// non-positive corner Jacobian in the current configuration (of the 8 corner nodes;
// a 20-node element's mid-edge nodes are not looked at): at each corner a,
// det[e_xi, e_eta, e_zeta] with e the edges from a towards its three neighbours,
// oriented along +xi, +eta, +zeta (the trilinear map's Jacobian at a, times 8).
// All eight positive is the usual validity test of a hexahedron. The safety radius:
// moving the nodes by at most delta changes each edge by at most 2 delta, so the
// corner matrix J by ||E||_2 <= ||E||_F <= 2 sqrt(3) delta, and det J keeps its sign
// while that stays below sigma_min(J) >= det J / ||J||_F^2 (as sigma_1 sigma_2 <=
// ||J||_F^2); hence delta < min over corners of det J / (2 sqrt(3) ||J||_F^2).
// One element at a time: the simple form the packed pass below is tested against.
InvertedElement find_inverted_element(const ElementBlock& block, std::uint32_t element_begin,
                                      std::uint32_t element_end, const NodalVectors& x_ref,
                                      const NodalVectors& u);
// The whole block, in packs of elements on the threads: the same element and corner.
InvertedElement find_inverted_element(const ElementBlock& block, const NodalVectors& x_ref,
                                      const NodalVectors& u);

// Both in one pass over the corners: what current_time_step and find_inverted_element
// return (the step's bits are current_time_step's).
CornerChecks check_corners(const ElementBlock& block, const NodalVectors& x_ref, const NodalVectors& u);

// The same checks run by the block's next element pass on the corners its kernels
// gather (a block whose loop does: ElementBlock::corners_in_pass), in place of a pass
// of their own: its step, its inversion check or both. corner_checks_of_pass, after
// that pass, returns what check_corners would (the same bits) and clears the request.
void request_corner_checks(const ElementBlock& block, const NodalVectors& x_ref, bool step, bool inversion);
CornerChecks corner_checks_of_pass(const ElementBlock& block);

}  // namespace exdyn::element
