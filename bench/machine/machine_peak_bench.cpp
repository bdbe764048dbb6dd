// The machine's limits for the roofline of docs/performance.md, on one core:
//   - floating-point throughput with independent accumulators (no dependency
//     chain limits the rate): SSE2 packed-double add + mul (the project's
//     -march=x86-64-v2 has no FMA and no AVX), and, when the CPU has them,
//     AVX2 + FMA (compiled for that target only in these functions, run only if
//     __builtin_cpu_supports says so);
//   - a STREAM-like triad a = b + s c at sizes in L1, L2, L3 and far above the
//     last-level cache (memory bandwidth).
// Counters: GFLOP/s (flops / CPU second) and bytes_per_second (STREAM bytes:
// 24 per triad element; write-allocate traffic, 32 per element, is not counted).
#include <benchmark/benchmark.h>
#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

constexpr std::int64_t inner_iterations = 1 << 16;

// An empty asm that "may change" its operands: the compiler must keep every
// chain as written (no merging of chains, no folding across iterations) while
// the arithmetic itself is still compiler-generated for the target.
template <class Value>
inline void keep_in_register(Value& value) {
  asm volatile("" : "+x"(value));
}
template <class... Values>
inline void keep_in_registers(Values&... values) {
  (keep_in_register(values), ...);
}

// 7 add chains + 7 mul chains of 2-wide SSE2 doubles: with a latency of 3
// cycles and two add and two mul pipes (AMD Zen 3/4), six chains of each keep
// every pipe busy; 7 + 7 accumulators and the two constants fill the 16 xmm
// registers. x <- x * (1 + 1e-9) grows by about a factor e per second of running:
// far from overflow for any sensible --benchmark_min_time.
void sse2_add_mul(benchmark::State& state) {
  const __m128d add = _mm_set1_pd(1.0e-12), mul = _mm_set1_pd(1.0 + 1.0e-9);
  __m128d a0 = _mm_set1_pd(1.0), a1 = _mm_set1_pd(1.1), a2 = _mm_set1_pd(1.2), a3 = _mm_set1_pd(1.3),
          a4 = _mm_set1_pd(1.4), a5 = _mm_set1_pd(1.5), a6 = _mm_set1_pd(1.6);
  __m128d m0 = _mm_set1_pd(2.0), m1 = _mm_set1_pd(2.1), m2 = _mm_set1_pd(2.2), m3 = _mm_set1_pd(2.3),
          m4 = _mm_set1_pd(2.4), m5 = _mm_set1_pd(2.5), m6 = _mm_set1_pd(2.6);
  for (auto _ : state) {
    for (std::int64_t i = 0; i < inner_iterations; ++i) {
      a0 = _mm_add_pd(a0, add), m0 = _mm_mul_pd(m0, mul), a1 = _mm_add_pd(a1, add), m1 = _mm_mul_pd(m1, mul);
      a2 = _mm_add_pd(a2, add), m2 = _mm_mul_pd(m2, mul), a3 = _mm_add_pd(a3, add), m3 = _mm_mul_pd(m3, mul);
      a4 = _mm_add_pd(a4, add), m4 = _mm_mul_pd(m4, mul), a5 = _mm_add_pd(a5, add), m5 = _mm_mul_pd(m5, mul);
      a6 = _mm_add_pd(a6, add), m6 = _mm_mul_pd(m6, mul);
      keep_in_registers(a0, a1, a2, a3, a4, a5, a6);
      keep_in_registers(m0, m1, m2, m3, m4, m5, m6);
    }
  }
  __m128d sum = _mm_add_pd(_mm_add_pd(_mm_add_pd(a0, a1), _mm_add_pd(a2, a3)), _mm_add_pd(a4, a5));
  sum = _mm_add_pd(sum, _mm_add_pd(_mm_add_pd(_mm_add_pd(m0, m1), _mm_add_pd(m2, m3)), _mm_add_pd(m4, m5)));
  sum = _mm_add_pd(sum, _mm_add_pd(a6, m6));
  benchmark::DoNotOptimize(sum);
  // 14 packed operations x 2 lanes per inner iteration.
  const double flops = 28.0 * static_cast<double>(inner_iterations);
  state.counters["GFLOP/s"] = benchmark::Counter(flops * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

// Adds only (12 chains): one half of the add + mul mix, to see which pipes the
// mix uses.
void sse2_add_only(benchmark::State& state) {
  const __m128d add = _mm_set1_pd(1.0e-12);
  __m128d a0 = _mm_set1_pd(1.0), a1 = _mm_set1_pd(1.1), a2 = _mm_set1_pd(1.2), a3 = _mm_set1_pd(1.3),
          a4 = _mm_set1_pd(1.4), a5 = _mm_set1_pd(1.5), a6 = _mm_set1_pd(1.6), a7 = _mm_set1_pd(1.7),
          a8 = _mm_set1_pd(1.8), a9 = _mm_set1_pd(1.9), a10 = _mm_set1_pd(2.0), a11 = _mm_set1_pd(2.1);
  for (auto _ : state) {
    for (std::int64_t i = 0; i < inner_iterations; ++i) {
      a0 = _mm_add_pd(a0, add), a1 = _mm_add_pd(a1, add), a2 = _mm_add_pd(a2, add), a3 = _mm_add_pd(a3, add);
      a4 = _mm_add_pd(a4, add), a5 = _mm_add_pd(a5, add), a6 = _mm_add_pd(a6, add), a7 = _mm_add_pd(a7, add);
      a8 = _mm_add_pd(a8, add), a9 = _mm_add_pd(a9, add), a10 = _mm_add_pd(a10, add),
      a11 = _mm_add_pd(a11, add);
      keep_in_registers(a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11);
    }
  }
  __m128d sum = _mm_add_pd(_mm_add_pd(_mm_add_pd(a0, a1), _mm_add_pd(a2, a3)), _mm_add_pd(a4, a5));
  sum = _mm_add_pd(sum, _mm_add_pd(_mm_add_pd(_mm_add_pd(a6, a7), _mm_add_pd(a8, a9)), _mm_add_pd(a10, a11)));
  benchmark::DoNotOptimize(sum);
  const double flops = 24.0 * static_cast<double>(inner_iterations);
  state.counters["GFLOP/s"] = benchmark::Counter(flops * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

// One dependent chain of adds: one add per add latency. With the latency of the
// CPU's manual (3 cycles for addpd on AMD Zen 2/3/4, 4 on Intel Skylake) this
// gives the core clock, which the VM does not show: GHz = latency x Gadds/s.
void sse2_add_latency(benchmark::State& state) {
  const __m128d add = _mm_set1_pd(1.0e-12);
  __m128d a = _mm_set1_pd(1.0);
  for (auto _ : state) {
    for (std::int64_t i = 0; i < inner_iterations; ++i) {
      a = _mm_add_pd(a, add), a = _mm_add_pd(a, add), a = _mm_add_pd(a, add), a = _mm_add_pd(a, add);
      keep_in_registers(a);
    }
  }
  double result = _mm_cvtsd_f64(a);  // (DoNotOptimize(a) would keep a in memory inside the loop)
  benchmark::DoNotOptimize(result);
  state.counters["Gadds/s"] = benchmark::Counter(4.0 * static_cast<double>(inner_iterations) * 1e-9,
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

// AVX2 + FMA: 10 chains of 4-wide fused multiply-adds (latency 4-5 cycles,
// two FMA pipes). Compiled for avx2,fma here only.
__attribute__((target("avx2,fma"))) void avx2_fma_kernel(benchmark::State& state) {
  const __m256d mul = _mm256_set1_pd(1.0000001), add = _mm256_set1_pd(-1.0e-7);
  __m256d a0 = _mm256_set1_pd(1.0), a1 = _mm256_set1_pd(1.1), a2 = _mm256_set1_pd(1.2),
          a3 = _mm256_set1_pd(1.3), a4 = _mm256_set1_pd(1.4), a5 = _mm256_set1_pd(1.5),
          a6 = _mm256_set1_pd(1.6), a7 = _mm256_set1_pd(1.7), a8 = _mm256_set1_pd(1.8),
          a9 = _mm256_set1_pd(1.9);
  for (auto _ : state) {
    for (std::int64_t i = 0; i < inner_iterations; ++i) {
      // x <- x * 1.0000001 - 1e-7 has the fixed point 1: bounded for ever.
      a0 = _mm256_fmadd_pd(a0, mul, add), a1 = _mm256_fmadd_pd(a1, mul, add);
      a2 = _mm256_fmadd_pd(a2, mul, add), a3 = _mm256_fmadd_pd(a3, mul, add);
      a4 = _mm256_fmadd_pd(a4, mul, add), a5 = _mm256_fmadd_pd(a5, mul, add);
      a6 = _mm256_fmadd_pd(a6, mul, add), a7 = _mm256_fmadd_pd(a7, mul, add);
      a8 = _mm256_fmadd_pd(a8, mul, add), a9 = _mm256_fmadd_pd(a9, mul, add);
      keep_in_registers(a0, a1, a2, a3, a4, a5, a6, a7, a8, a9);
    }
  }
  __m256d sum = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(a0, a1), _mm256_add_pd(a2, a3)),
                              _mm256_add_pd(_mm256_add_pd(a4, a5), _mm256_add_pd(a6, a7)));
  sum = _mm256_add_pd(sum, _mm256_add_pd(a8, a9));
  benchmark::DoNotOptimize(sum);
  // 10 FMAs x 4 lanes x 2 flops per inner iteration.
  const double flops = 80.0 * static_cast<double>(inner_iterations);
  state.counters["GFLOP/s"] = benchmark::Counter(flops * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

void avx2_fma(benchmark::State& state) {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    state.SkipWithError("the CPU has no AVX2 + FMA");
    return;
  }
  avx2_fma_kernel(state);
}

// a = b + s c over n doubles per array (3 arrays): 2 flops and 24 STREAM bytes per element.
void triad(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  for (auto _ : state) {
    double* __restrict out = a.data();
    const double* __restrict x = b.data();
    const double* __restrict y = c.data();
    for (std::size_t i = 0; i < n; ++i) out[i] = x[i] + s * y[i];
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(a.data());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(24 * n));
  state.counters["GFLOP/s"] =
      benchmark::Counter(2.0 * static_cast<double>(n) * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["MiB_total"] = static_cast<double>(24 * n) / (1024.0 * 1024.0);
}

BENCHMARK(sse2_add_mul);
BENCHMARK(sse2_add_only);
BENCHMARK(sse2_add_latency);
BENCHMARK(avx2_fma);
// 3 x n doubles: 24 KiB (L1), 384 KiB (L2), 6 MiB (L3), 384 MiB (memory).
BENCHMARK(triad)->Arg(1 << 10)->Arg(1 << 14)->Arg(1 << 18)->Arg(1 << 24)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
