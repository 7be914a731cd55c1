#include "core/number_format.h"

#include <cmath>
#include <cstring>

#include <fmt/format.h>

namespace relief {

namespace {
constexpr std::uint64_t kPow10[] = {1,      10,      100,      1000,      10000,
                                    100000, 1000000, 10000000, 100000000, 1000000000};
// Two digits at a time halves the divisions: the writer is on the hot path
// of emitting millions of vertices.
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Writes `v` with exactly `width` digits (zero padded) ending at `end`.
inline void writeDigitsBackward(char* end, std::uint64_t v, int width) {
    while (width >= 2) {
        std::memcpy(end - 2, kDigitPairs + 2 * (v % 100), 2);
        v /= 100;
        end -= 2;
        width -= 2;
    }
    if (width == 1) end[-1] = static_cast<char>('0' + v % 10);
}

inline int digitCount(std::uint64_t v) {
    int n = 1;
    while (v >= 10) {
        v /= 10;
        ++n;
    }
    return n;
}
}  // namespace

char* writeUnsigned(char* out, std::uint64_t value) {
    const int n = digitCount(value);
    writeDigitsBackward(out + n, value, n);
    return out + n;
}

char* writeFixed(char* out, double value, int decimals) {
    const std::uint64_t scale = kPow10[decimals];
    const double scaled = std::fabs(value) * static_cast<double>(scale);
    // Past 2^63 (or NaN) the integer cast is undefined: such a value (which
    // the stages refuse before it gets here) is written in exponent form, at
    // most 14 characters.
    if (!(scaled < 9.2e18)) return fmt::format_to(out, "{:.6e}", value);
    const auto units = static_cast<std::uint64_t>(scaled + 0.5);
    if (units == 0) {
        *out++ = '0';
        return out;
    }
    if (value < 0) *out++ = '-';
    out = writeUnsigned(out, units / scale);
    if (decimals > 0) {
        *out++ = '.';
        writeDigitsBackward(out + decimals, units % scale, decimals);
        out += decimals;
    }
    return out;
}

std::string formatShortest(double value) { return fmt::format("{}", value); }

std::string fixedNumber(double value, int decimals) {
    char buf[40];
    return std::string(buf, writeFixed(buf, value, decimals));
}

std::string fixedVector(double x, double y, double z, int decimals) {
    char buf[128];
    char* p = buf;
    *p++ = '<';
    p = writeFixed(p, x, decimals);
    *p++ = ',';
    p = writeFixed(p, y, decimals);
    *p++ = ',';
    p = writeFixed(p, z, decimals);
    *p++ = '>';
    return std::string(buf, p);
}

}  // namespace relief
