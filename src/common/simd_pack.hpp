// Packs of doubles for the kernels that run several elements or nodes at once, one per
// vector lane (GCC vector extensions: the operators act lane by lane), and the loads
// of their interleaved data.
#pragma once

#include <cstring>

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

}  // namespace exdyn
