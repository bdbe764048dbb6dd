// The corner checks of one pack of 8-node elements in the vector lanes (Pack<Lanes>):
// the stable step of the current configuration and the inversion check
// (corner_checks.hpp has their equations). Two passes run them: the pass over the
// corners alone (corner_checks.cpp) and the element pass of the 8-node law loops,
// on the corners the kernel already gathers (element_loop.hpp): the same arithmetic on
// the same x = x_ref + u, so the same bits.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "common/simd_pack.hpp"
#include "element/element_block.hpp"
#include "element/hex8_constitutive.hpp"

namespace exdyn::element {

namespace corner {
// Neighbours of each corner along xi, eta, zeta, and the sign that orients the edge
// towards +xi, +eta, +zeta (VTK order: 0-3 at zeta = -1, 4-7 at zeta = +1).
inline constexpr int neighbour[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                        {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
// -sx sy sz of the corner at (sx, sy, sz): +1 where all three edges already point the + way.
inline constexpr double orientation[8] = {1.0, -1.0, 1.0, -1.0, -1.0, 1.0, -1.0, 1.0};
}  // namespace corner

// The checks of the packs of one chunk [begin, end) of a block (begin a multiple of
// Lanes), pack after pack in element order: add each pack's corners, then finish.
template <int Lanes>
class PackCorners {
 public:
  using Real = Pack<Lanes>;

  PackCorners(const ElementBlock& block, std::uint32_t begin)
      : scale_(block.step_scale / block.material.dilatational_wave_speed()) {
    result_.step = {std::numeric_limits<double>::infinity(), block.first_element + begin};
  }

  // x: the corners of the elements first .. first + Lanes - 1 (a lane past the block's
  // end repeats an element of the block). The step counts the lanes before `end`.
  // Under time.erode (block.failure.erode_step > 0) every pass first marks the live
  // elements that are too distorted to go on (mark_distorted); those set no step and
  // are not reported inverted: they fail and are eroded instead.
  void add(const BasicElementVectors<Real>& x, const ElementBlock& block, std::uint32_t first,
           std::uint32_t end, bool step, bool inversion) {
    const bool erode = block.failure.erode_step > 0.0;
    Real dt{};
    if (step || erode)
      dt = scale_ * hex8::current_characteristic_length(x);  // L_e / c1 times the family's scale, s
    // The corner determinants, once for the rule and the inversion check.
    const bool inverting = inversion && !result_.inverted.found;
    Real det[8], frobenius2[8];
    if (erode || inverting) corner_determinants(x, det, frobenius2);
    Real kept = Real{} + 1.0;  // 0 in the lanes marked distorted
    if (erode) kept = mark_distorted(det, dt, block, first, end);
    if (step) {
      if (erode) dt = select(kept > 0.0, dt, Real{} + std::numeric_limits<double>::infinity());
      if (any_lane(dt < result_.step.dt))  // most packs set no new smallest: one compare
        for (int lane = 0; lane < Lanes && first + std::uint32_t(lane) < end; ++lane)
          if (dt[lane] < result_.step.dt)
            result_.step = {dt[lane], block.first_element + first + std::uint32_t(lane)};
    }
    if (inverting) check(det, frobenius2, first, block, kept);
  }

  // The chunk's result: the first smallest step; the first inverted element, or the
  // safety radius det J / (2 sqrt(3) ||J||_F^2) of the smallest corner (m).
  CornerChecks finish(bool inversion) {
    if (inversion && !result_.inverted.found) {
      double ratio = smallest_ratio_[0];  // lanes past the block's end repeat an element inside it
      for (int lane = 1; lane < Lanes; ++lane) ratio = std::min(ratio, double(smallest_ratio_[lane]));
      result_.inverted.safety_radius = ratio / (2.0 * std::sqrt(3.0));
    }
    return result_;
  }

 private:
  // The signed corner determinants of a pack: at each corner a, det[e_xi, e_eta,
  // e_zeta] of the edges towards its neighbours (corner_checks.hpp), and ||J||_F^2.
  static void corner_determinants(const BasicElementVectors<Real>& x, Real (&det)[8], Real (&frobenius2)[8]) {
    for (int a = 0; a < 8; ++a) {
      const int i = corner::neighbour[a][0], j = corner::neighbour[a][1], k = corner::neighbour[a][2];
      const Real ax = x.x[i] - x.x[a], ay = x.y[i] - x.y[a], az = x.z[i] - x.z[a];
      const Real bx = x.x[j] - x.x[a], by = x.y[j] - x.y[a], bz = x.z[j] - x.z[a];
      const Real cx = x.x[k] - x.x[a], cy = x.y[k] - x.y[a], cz = x.z[k] - x.z[a];
      det[a] = corner::orientation[a] *
               (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx));
      frobenius2[a] = ax * ax + ay * ay + az * az + bx * bx + by * by + bz * bz + cx * cx + cy * cy + cz * cz;
    }
  }

  // time.erode's rule (docs/theory.md, "Damage and erosion"): a live element of a block
  // that can fail whose stable step dt (without the Courant factor) is below
  // block.failure.erode_step, or with a corner det J <= 0, is marked in
  // block.failure.distorted (the damage pass fails it). Returns 1 in the lanes kept,
  // 0 in those marked.
  static Real mark_distorted(const Real (&det)[8], const Real& dt, const ElementBlock& block,
                             std::uint32_t first, std::uint32_t end) {
    Real smallest = det[0];
    for (int a = 1; a < 8; ++a) smallest = select(det[a] < smallest, det[a], smallest);
    const double limit = block.failure.erode_step;
    Real kept = Real{} + 1.0;
    if (!any_lane(dt < limit) && !any_lane((smallest > 0.0) == 0)) return kept;  // the usual pack
    ElementFailure& f = block.failure;  // mutable: each element is marked by its own chunk
    for (int lane = 0; lane < Lanes && first + std::uint32_t(lane) < std::min(end, block.count); ++lane) {
      const std::uint32_t e = first + std::uint32_t(lane);
      if (f.status[e] == ElementStatus::eroded || (dt[lane] >= limit && smallest[lane] > 0.0)) continue;
      f.distorted[e] = 1;
      kept[lane] = 0.0;
    }
    return kept;
  }

  // The inversion check of a pack (find_inverted_element's arithmetic, lane by lane):
  // the first lane and corner with det <= 0 (or not a number), else the running
  // smallest det / ||J||_F^2; lanes with kept = 0 (marked distorted) are left out.
  void check(Real (&det)[8], const Real (&frobenius2)[8], std::uint32_t first, const ElementBlock& block,
             const Real& kept) {
    const Real one = Real{} + 1.0, infinity = Real{} + std::numeric_limits<double>::infinity();
    bool bad = false;
    for (int a = 0; a < 8; ++a) {
      det[a] = select(kept > 0.0, det[a], one);
      bad = bad || any_lane((det[a] > 0.0) == 0);
      const Real ratio = select(kept > 0.0, det[a] / frobenius2[a], infinity);
      smallest_ratio_ = select(ratio < smallest_ratio_, ratio, smallest_ratio_);
    }
    if (!bad) return;
    for (int lane = 0; lane < Lanes && first + std::uint32_t(lane) < block.count; ++lane)
      for (int a = 0; a < 8; ++a)
        if (!(det[a][lane] > 0.0)) {
          result_.inverted = {true, block.first_element + first + std::uint32_t(lane), a, det[a][lane], 0.0};
          return;
        }
  }

  double scale_;  // block.step_scale / c1, s/m
  CornerChecks result_;
  Real smallest_ratio_ = Real{} + std::numeric_limits<double>::infinity();  // det J / ||J||_F^2, m
};

}  // namespace exdyn::element
