// Coulomb friction of one slave point in contact (docs/contact.md, "Friction"):
// a regularised stick, a tangential penalty spring between the slave point and its
// stick anchor on the master side, with a return to the Coulomb cone.
//
//   trial:  F_t* = -k_t g_t,  g_t = (I - n n)(x_s - x_anchor)           (N)
//   stick:  |F_t*| <= mu F_n  ->  F_t = F_t*, the anchor stays
//   slip:   F_t = mu F_n F_t* / |F_t*|, the anchor follows the slave point along g_t
//           until the spring holds exactly mu F_n: it moves by (1 - mu F_n / |F_t*|) g_t,
//           and that slip dissipates mu F_n times its length (J)
//
// with mu = mu_d + (mu_s - mu_d) exp(-d |v_slip|), v_slip the tangential part of the
// relative velocity (m/s). k_t is the normal stiffness of the same point: the spring
// matrix k n n + k_t (I - n n) is then k I, whose frequency the normal stiffness's caps
// already keep stable (penalty.hpp).
#pragma once

#include <cmath>
#include <cstdint>

#include "contact/segment.hpp"

namespace exdyn::contact {

struct FrictionLaw {
  bool enabled = false;
  double static_coefficient = 0.0;   // mu_s
  double dynamic_coefficient = 0.0;  // mu_d
  double decay = 0.0;                // d, s/m

  // mu at slip speed |v_slip| (m/s).
  double coefficient(double slip_speed) const {
    if (decay == 0.0) return static_coefficient;  // exp(0) = 1
    return dynamic_coefficient + (static_coefficient - dynamic_coefficient) * std::exp(-decay * slip_speed);
  }
};

// Where a slave point's tangential spring is anchored: a point (segment, xi1, xi2) of
// the master surface, so that it moves with the master side; segment -1: none (the
// point is not in contact, or came into contact this step).
struct Anchor {
  std::int64_t segment = -1;
  Xi xi{};
};

struct TangentialForce {
  Vec3 force{};              // F_t on the slave point, N
  Vec3 anchor_shift{};       // how far the anchor moves (0 while sticking), m
  double dissipation = 0.0;  // mu F_n |anchor_shift|, J
  bool slip = false;
};

// The return mapping above: tangent_gap g_t (m, tangential), k_t (N/m), F_n (N, >= 0),
// mu at this slip speed.
inline TangentialForce coulomb_force(Vec3 tangent_gap, double tangent_stiffness, double normal_force,
                                     double mu) {
  TangentialForce result;
  const Vec3 trial = -tangent_stiffness * tangent_gap;
  const double trial_size = norm(trial), limit = mu * normal_force;
  if (trial_size <= limit) {
    result.force = trial;
    return result;
  }
  const double kept = limit / trial_size;  // the fraction of g_t the spring keeps
  result.force = kept * trial;
  result.anchor_shift = (1.0 - kept) * tangent_gap;
  result.dissipation = limit * norm(result.anchor_shift);
  result.slip = true;
  return result;
}

// The tangential part (I - n n) a of a, n of unit length.
inline Vec3 tangential_part(Vec3 a, Vec3 n) { return a - dot(a, n) * n; }

}  // namespace exdyn::contact
