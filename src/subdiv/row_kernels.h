#pragma once
// The inner loops of the fused refinement level (refine.cpp), on rows seen as
// flat arrays of doubles (x, y, z, x, y, z, ...). The machine-specific code of
// the refiner lives here, chosen once at load time: AVX2 where the CPU has it,
// plain C++ elsewhere (an AVX-512 variant of the sums measured slower on this
// machine's Zen 5: 9.9 against 7.8 ms for dlg4, 257^2 to depth 3). Every
// variant computes the same products and sums in the same order (and the
// build turns off FMA contraction), so a refined grid is bit-identical on any
// x86-64 machine; the tests check it.
#include <cstddef>
#include <vector>

namespace relief::subdiv {

/// The instruction sets the kernels are built for (all give the same bits).
enum class KernelIsa { Baseline = 0, Avx2 = 1 };

/// The best the CPU has: what the kernels use unless told otherwise.
KernelIsa bestKernelIsa();
/// Uses `isa` (or the best the CPU has, if it lacks `isa`) from now on. For
/// tests and benchmarks that compare the sets; not while a refinement runs.
void useKernelIsa(KernelIsa isa);

/// out[e] = sum_j w[j] in[j][e] for e in [0, n), summed left to right, with
/// ordinary stores: for rows that are read again soon (they stay in cache).
void combineRows(double* out, const double* const* in, const std::vector<double>& w, size_t n);

/// The same sums, written with non-temporal (streaming) stores: each output
/// cache line goes to memory without first being read into the cache, as an
/// ordinary store's line is. For a level's output rows, which are written once
/// and not read again in this level. Call streamingDone() before anything
/// (another thread, the next level) reads them. The plain kernels, and rules
/// longer than 9 taps, use ordinary stores.
void combineRowsStreaming(double* out, const double* const* in, const std::vector<double>& w,
                          size_t n);

/// Orders the streaming stores of this thread before its later stores, so that
/// a barrier after it publishes them.
void streamingDone();

/// The m rules' new points of one row, interleaved into the refined row:
/// output point m i + r is point i of streams[r], for output points
/// [0, points). Every stream may be read for its first `readable` doubles
/// (at least what the output takes from it).
void interleavePoints(double* out, const double* const* streams, int m, long points,
                      long readable);

}  // namespace relief::subdiv
