// Packs of doubles for the kernels that run several elements or nodes at once, one per
// vector lane (GCC vector extensions: the operators act lane by lane), and the loads
// of their interleaved data.
#pragma once

#include <cstring>
#include <type_traits>

namespace exdyn {

// Lanes values side by side (elements, nodes), one per vector lane: 2 under SSE (x86-64-v2),
// 4 under AVX2 (x86-64-v3), 8 under AVX-512 (x86-64-v4). The element kernels that
// are templates on the value type (hex8, hex8r) run on packs of elements with it, and
// on single elements with double; the nodal update runs on packs of nodes.
// (One specialisation per width: g++ drops vector_size on a typedef whose size
// depends on a template parameter.)
template <int Lanes>
struct PackOf;
template <>
struct PackOf<2> {
  using type = double __attribute__((vector_size(16)));
};
template <>
struct PackOf<4> {
  using type = double __attribute__((vector_size(32)));
};
template <>
struct PackOf<8> {
  using type = double __attribute__((vector_size(64)));
};
template <int Lanes>
using Pack = typename PackOf<Lanes>::type;
using Pack2 = Pack<2>;

// Integer lanes of the same width: the results of comparing packs, masks for the
// vector select `mask ? a : b`, and lane indices for __builtin_shuffle.
template <int Lanes>
struct IntPackOf;
template <>
struct IntPackOf<2> {
  using type = long long __attribute__((vector_size(16)));
};
template <>
struct IntPackOf<4> {
  using type = long long __attribute__((vector_size(32)));
};
template <>
struct IntPackOf<8> {
  using type = long long __attribute__((vector_size(64)));
};
template <int Lanes>
using IntPack = typename IntPackOf<Lanes>::type;

// Elements in one value: 1 for double, Lanes for Pack<Lanes>.
template <class Real>
inline constexpr int lanes_of = static_cast<int>(sizeof(Real) / sizeof(double));

// Value k of an element's reference data: data[k] for one element; for a pack of
// elements, whose data are interleaved, the Lanes values at data[Lanes k].
template <class Real>
inline Real load(const double* data, int k) {
  if constexpr (lanes_of<Real> == 1) {
    return data[k];
  } else {
    Real value;
    std::memcpy(&value, data + lanes_of<Real> * k, sizeof value);
    return value;
  }
}

// data[0..Lanes) = value (unaligned).
template <class Real>
inline void store(double* data, const Real& value) {
  std::memcpy(data, &value, sizeof value);
}

// Lane-wise helpers for the kernels written for both double and Pack<L>: the same
// source runs one element or a pack of them.

// value of lane `lane` (0 for a double), and setting it.
template <class Real>
inline double lane(const Real& value, int index) {
  if constexpr (lanes_of<Real> == 1) {
    (void)index;
    return value;
  } else {
    return value[index];
  }
}
template <class Real>
inline void set_lane(Real& value, int index, double lane_value) {
  if constexpr (lanes_of<Real> == 1) {
    (void)index;
    value = lane_value;
  } else {
    value[index] = lane_value;
  }
}

// condition ? a : b lane by lane, for the conditions of comparisons of packs (a < b).
template <class Real, class Mask>
inline Real select(const Mask& condition, const Real& a, const Real& b) {
  return condition ? a : b;  // for packs GCC's vector select (a mask of -1 or 0 per lane)
}

template <class Real>
inline Real lane_max(const Real& a, const Real& b) {
  return select(a > b, a, b);
}

// sqrt lane by lane (vsqrtpd where the compiler vectorises the loop).
template <class Real>
inline Real lane_sqrt(const Real& value) {
  if constexpr (lanes_of<Real> == 1) {
    return __builtin_sqrt(value);
  } else {
    // Every lane is written below. GCC 12 can take the loop for a partial write where
    // it inlines this into a large kernel; a zero start instead (to quiet it) kept it
    // from becoming one vsqrtpd: the hex8r finite kernel ran 20 % slower.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
    Real result;
    for (int k = 0; k < lanes_of<Real>; ++k) result[k] = __builtin_sqrt(value[k]);
    return result;
#pragma GCC diagnostic pop
  }
}

// True when any lane of a comparison's mask is set.
template <class Mask>
inline bool any_lane(const Mask& mask) {
  if constexpr (std::is_integral_v<Mask>) {
    return mask != 0;
  } else {
    for (int k = 0; k < int(sizeof(Mask) / sizeof(long long)); ++k)
      if (mask[k] != 0) return true;
    return false;
  }
}

}  // namespace exdyn
