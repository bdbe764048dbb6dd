// The instruction set the element kernels run with (docs/performance.md, "Vector
// kernels"). The shipped binary is built for x86-64-v2 (SSE4.2) and runs on any
// x86-64 machine of the last fifteen years; the element loops are compiled three
// times (element_isa.hpp), and the best version this CPU can run is chosen once, at
// start-up, before the element blocks are built:
//   x86-64-v2  SSE up to 4.2, 16 vector registers of 2 doubles
//   x86-64-v3  AVX2 and FMA, 16 registers of 4 doubles, fused multiply-adds
//   x86-64-v4  AVX-512, 32 registers of 8 doubles
// `exdyn run --isa NAME` or the environment variable EXDYN_ISA=NAME picks a lower one
// (to compare, or to reproduce another machine's bits); asking for one this CPU lacks
// is bad input. Results on different ISAs agree to round-off (1e-12 relative, a test),
// not bit for bit: FMA rounds once where a multiply and an add round twice.
#pragma once

#include <array>
#include <atomic>
#include <cstdlib>
#include <string>
#include <string_view>

#include "common/errors.hpp"

namespace exdyn {

enum class Isa { x86_64_v2 = 0, x86_64_v3 = 1, x86_64_v4 = 2 };

inline constexpr std::array<Isa, 3> all_isas{Isa::x86_64_v2, Isa::x86_64_v3, Isa::x86_64_v4};

constexpr const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v2:
      return "x86-64-v2";
    case Isa::x86_64_v3:
      return "x86-64-v3";
    case Isa::x86_64_v4:
      return "x86-64-v4";
  }
  return "x86-64-v2";
}

constexpr const char* isa_description(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v2:
      return "SSE4.2";
    case Isa::x86_64_v3:
      return "AVX2 + FMA";
    case Isa::x86_64_v4:
      return "AVX-512";
  }
  return "SSE4.2";
}

// Whether this CPU runs code built for `isa`.
inline bool isa_available(Isa isa) {
  __builtin_cpu_init();
  switch (isa) {
    case Isa::x86_64_v2:
      return true;  // the build's own baseline: the program would not have started otherwise
    case Isa::x86_64_v3:
      return __builtin_cpu_supports("x86-64-v3");
    case Isa::x86_64_v4:
      return __builtin_cpu_supports("x86-64-v4");
  }
  return false;
}

inline Isa best_available_isa() {
  if (isa_available(Isa::x86_64_v4)) return Isa::x86_64_v4;
  if (isa_available(Isa::x86_64_v3)) return Isa::x86_64_v3;
  return Isa::x86_64_v2;
}

// The ISA of a name (x86-64-v2, x86-64-v3, x86-64-v4); InputError naming `where`
// for another name or one this CPU lacks.
inline Isa parse_isa(std::string_view name, const std::string& where) {
  for (const Isa isa : all_isas) {
    if (name != isa_name(isa)) continue;
    if (!isa_available(isa))
      throw InputError(where + ": this CPU cannot run " + std::string(name) + " (" + isa_description(isa) +
                       "); the best it runs is " + isa_name(best_available_isa()));
    return isa;
  }
  throw InputError(where + ": unknown instruction set '" + std::string(name) +
                   "' (expected x86-64-v2, x86-64-v3 or x86-64-v4)");
}

namespace detail {
inline std::atomic<int> selected_isa{-1};  // -1: not chosen yet
}

// Chooses the ISA of the element blocks built from now on.
inline void select_isa(Isa isa) { detail::selected_isa.store(static_cast<int>(isa)); }

// The ISA chosen: by select_isa, else EXDYN_ISA, else the best available.
inline Isa selected_isa() {
  int chosen = detail::selected_isa.load();
  if (chosen < 0) {
    const char* name = std::getenv("EXDYN_ISA");
    const Isa isa = name != nullptr && *name != '\0' ? parse_isa(name, "EXDYN_ISA") : best_available_isa();
    chosen = static_cast<int>(isa);
    detail::selected_isa.store(chosen);
  }
  return static_cast<Isa>(chosen);
}

}  // namespace exdyn
