#pragma once
// Locale-free number formatting for everything relief writes (SDL, CSV, JSON
// headers). One function per shape, so a given double always gives the same
// bytes, whatever the process locale: the .pov output is stable byte for byte.
#include <cstdint>
#include <string>

namespace relief {

/// Appends `value` in fixed notation with exactly `decimals` (0..9) digits after
/// the point, rounded half away from zero; "-0" is written as "0". Precondition:
/// |value| * 10^decimals < 9.2e18 (callers write scene units, far below that).
/// Writes at most 32 characters at `out` and returns the end.
char* writeFixed(char* out, double value, int decimals);

/// `value` with `decimals` fixed decimals (writeFixed), as SDL's numbers are written.
std::string fixedNumber(double value, int decimals = 6);

/// "<x,y,z>" with `decimals` fixed decimals each (writeFixed), as POV-Ray's
/// vectors are written.
std::string fixedVector(double x, double y, double z, int decimals);

/// Appends an unsigned integer in decimal. Writes at most 20 characters.
char* writeUnsigned(char* out, std::uint64_t value);

/// Shortest round-trip representation (fmt's "{}"), for headers and reports.
std::string formatShortest(double value);

}  // namespace relief
