#pragma once
// The seconds a stage took, as the progress lines and the sidecars report them:
// on the steady clock, which no change of the system's time moves.
#include <chrono>

namespace relief {

using Clock = std::chrono::steady_clock;

/// Seconds since `t0`, a reading of Clock.
inline double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace relief
