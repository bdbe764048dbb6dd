// The element loops for each instruction set (common/isa.hpp). A family writes its
// loop once and stores `for_isa<Loop>(selected_isa())` in block.loop: the x86-64-v3
// and x86-64-v4 versions are the same source, inlined whole (`flatten`: the loop, its
// kernel and every function they call) into a function compiled for that ISA, so the
// kernels get AVX2 + FMA or AVX-512's 32 registers while the rest of the program, and
// the binary's baseline, stay x86-64-v2. The baseline version is flattened too, so the
// versions differ only in the instructions.
#pragma once

#include <cstdint>

#include "common/isa.hpp"
#include "common/nodal_vectors.hpp"
#include "element/element_block.hpp"

namespace exdyn::element {

// Each version starts on a 64-byte line (gnu::aligned), so that where the linker puts it,
// which moves with every change elsewhere in the program, does not move its inner loops
// across fetch lines: the crushed tube's element pass ran 7 % slower with the loop
// starting 48 bytes into a line than at its start (the same code, 0x...470 against
// 0x...180).
template <ElementLoopFn Loop>
[[gnu::flatten, gnu::aligned(64)]] ElementEnergies loop_x86_64_v2(const ElementBlock& block,
                                                                  std::uint32_t begin, std::uint32_t end,
                                                                  const NodalVectors& u, NodalVectors& f_int,
                                                                  double* stress) {
  return Loop(block, begin, end, u, f_int, stress);
}

template <ElementLoopFn Loop>
[[gnu::target("arch=x86-64-v3"), gnu::flatten, gnu::aligned(64)]] ElementEnergies loop_x86_64_v3(
    const ElementBlock& block, std::uint32_t begin, std::uint32_t end, const NodalVectors& u,
    NodalVectors& f_int, double* stress) {
  return Loop(block, begin, end, u, f_int, stress);
}

template <ElementLoopFn Loop>
[[gnu::target("arch=x86-64-v4"), gnu::flatten, gnu::aligned(64)]] ElementEnergies loop_x86_64_v4(
    const ElementBlock& block, std::uint32_t begin, std::uint32_t end, const NodalVectors& u,
    NodalVectors& f_int, double* stress) {
  return Loop(block, begin, end, u, f_int, stress);
}

// The version of Loop for `isa` (which the caller has checked this CPU runs).
template <ElementLoopFn Loop>
ElementLoopFn for_isa(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v4:
      return loop_x86_64_v4<Loop>;
    case Isa::x86_64_v3:
      return loop_x86_64_v3<Loop>;
    case Isa::x86_64_v2:
      break;
  }
  return loop_x86_64_v2<Loop>;
}

// The pack width of an ISA's loops: one 128-, 256- or 512-bit register of doubles.
inline int lanes_for(Isa isa) { return isa == Isa::x86_64_v4 ? 8 : isa == Isa::x86_64_v3 ? 4 : 2; }

// The loop for `isa`, from its versions for packs of 2, 4 and 8: each pack width is
// compiled for its own ISA alone (three functions, not nine).
template <ElementLoopFn Loop2, ElementLoopFn Loop4, ElementLoopFn Loop8>
ElementLoopFn packed_for_isa(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v4:
      return loop_x86_64_v4<Loop8>;
    case Isa::x86_64_v3:
      return loop_x86_64_v3<Loop4>;
    case Isa::x86_64_v2:
      break;
  }
  return loop_x86_64_v2<Loop2>;
}

}  // namespace exdyn::element
