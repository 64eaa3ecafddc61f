// Which implementation of each stage runs: the reference — scalar code that reads like the
// spec section it cites, general paths, one thread — or the fast paths beside it (AVX2
// kernels where the processor has them, specialised paths for common states, display-list
// blocks drawn as a whole, copies through lookup tables, several threads). Both give the same
// bits and counters: `passim run|program --reference` runs the reference, `--cross-check` runs
// both and compares them pass by pass (reports/cross_check.hpp), and the tests compare them
// kernel by kernel.
//
// The choice is process-wide and is made between runs, never during one (the raster lanes
// read it while they work).
#pragma once

#include "stages/avx2.hpp"

namespace passim {

struct KernelPaths {
  // The widest SIMD the kernels may use: none (the scalar reference), SSE2 (every x86-64
  // processor has it) or AVX2 (where the processor has it; SSE2 otherwise).
  enum class Simd { None, Sse2, Avx2 };
  Simd simd = Simd::Avx2;
  bool specialised = true;  // the specialised fast paths (else the general ones)
  static KernelPaths reference() { return {Simd::None, false}; }
  static KernelPaths fastest() { return {Simd::Avx2, true}; }
};

// The paths in force (fastest by default).
KernelPaths& kernel_paths();

// Whether a stage may run its AVX2 kernel now: the processor has AVX2 and AVX2 is allowed.
inline bool use_avx2() { return kernel_paths().simd == KernelPaths::Simd::Avx2 && cpu_has_avx2(); }
// Whether a stage may run its SSE2 kernel now (else its scalar reference).
inline bool use_sse2() { return kernel_paths().simd != KernelPaths::Simd::None; }
// Whether a stage may take a specialised path now.
inline bool use_specialised() { return kernel_paths().specialised; }

// Sets the paths for a scope (a test, one run of a cross-check), restoring them after.
class ScopedKernelPaths {
 public:
  explicit ScopedKernelPaths(KernelPaths paths) : saved_(kernel_paths()) { kernel_paths() = paths; }
  ~ScopedKernelPaths() { kernel_paths() = saved_; }
  ScopedKernelPaths(const ScopedKernelPaths&) = delete;
  ScopedKernelPaths& operator=(const ScopedKernelPaths&) = delete;

 private:
  KernelPaths saved_;
};

}  // namespace passim
