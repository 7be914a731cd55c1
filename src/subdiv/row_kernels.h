#pragma once
// The inner loops of the fused refinement level (refine.cpp), on rows seen as
// flat arrays of doubles (x, y, z, x, y, z, ...). The machine-specific code of
// the refiner lives here, chosen once at load time: AVX-512 or AVX2 where the
// CPU has them, plain C++ elsewhere. AVX-512 only adds the one-sweep row pass
// (RowSweep); the row sums stay AVX2 (512-bit sums measured slower for the
// streamed output rows, 9.9 against 7.8 ms for dlg4, and no faster in the row
// pass, on this machine's Zen 5). Every variant computes the same products and
// sums in the same order (and the build turns off FMA contraction), so a
// refined grid is bit-identical on any x86-64 machine; the tests check it.
#include <cstddef>
#include <memory>
#include <vector>

namespace relief::subdiv {

/// The instruction sets the kernels are built for (all give the same bits).
enum class KernelIsa { Baseline = 0, Avx2 = 1, Avx512 = 2 };

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

/// A rule as the kernels apply it: its nonzero weights and the offsets (in
/// points) of the coarse points they weigh.
struct Taps {
    std::vector<double> weights;
    std::vector<int> offsets;
    bool keepsOldPoint() const {
        return weights.size() == 1 && weights[0] == 1.0 && offsets[0] == 0;
    }
};

/// The m rules' new points of one row, interleaved into the refined row:
/// output point m i + r is point i of streams[r], for output points
/// [0, points). Every stream may be read for its first `readable` doubles
/// (at least what the output takes from it). A zero is written as +0 (the
/// refined rows carry no -0, whichever kernel made them).
void interleavePoints(double* out, const double* const* streams, int m, long points,
                      long readable);

struct SweepPattern;

/// One row refined along itself in one sweep (AVX-512): refined point m i + r
/// is rule r's sum of the points i + offsets[j] of the ghost-extended coarse
/// row, computed in its place, two points per vector, with no per-rule arrays
/// and no interleave. The same bits as the rules' sums then interleavePoints.
class RowSweep {
public:
    /// Prepares the sweep; it applies() only where the CPU has AVX-512 and the
    /// rules are binary or ternary and short (two refined points read at most
    /// 8 consecutive coarse points: the papers' rules do).
    explicit RowSweep(const std::vector<Taps>& rules);
    bool applies() const { return pattern_ != nullptr; }
    /// Writes refined points [0, points) to `out`, from the coarse row whose
    /// point 0 is at `first` (x, y, z each). Doubles [first - readableBefore,
    /// first + readableAfter) may be read, and must be finite.
    void refine(double* out, const double* first, long readableBefore, long readableAfter,
                long points) const;

private:
    std::vector<Taps> rules_;
    std::shared_ptr<const SweepPattern> pattern_;
};

}  // namespace relief::subdiv
