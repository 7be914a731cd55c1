#pragma once
// PNG files through libpng: written whole or not at all, with pixels only (no
// date, software or gamma chunks; the resolution only when one is given), so
// the same pixels give the same bytes.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace relief {

struct PngPixels {
    int width = 0, height = 0, channels = 1;  ///< channels: 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
    bool sixteenBit = false;     ///< 16-bit samples in native byte order (else 8-bit)
    const void* data = nullptr;  ///< rows top first, channels interleaved
    int compression = -1;        ///< zlib level 0..9 (0: stored); -1: zlib's default
    double dpi = 0;              ///< > 0: a pHYs chunk, so a word processor places it at this size
};

/// Writes `pixels` to `path` through a temporary file renamed into place.
/// Throws OutputError (core/output_set.h) at `path` when it cannot.
void writePngAtomically(const std::filesystem::path& path, const PngPixels& pixels);

struct PngImage8 {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> pixels;  ///< rows top first, channels interleaved
};

struct PngSize {
    int width = 0, height = 0;
};

/// Reads a PNG as 8-bit samples: palettes expand to RGB (RGBA with a tRNS
/// chunk), low bit depths to 8 and 16-bit samples are rounded to 8 bits.
/// With `expected`, a PNG of another size is refused from its header, before
/// anything is allocated for its pixels. Returns "" or the error, naming `path`.
std::string readPng8(const std::filesystem::path& path, PngImage8& image, const PngSize* expected = nullptr);

/// Re-encodes a PNG with its pixels only (no date, software or comment
/// chunks: POV-Ray's own PNG has its render date), so identical pixels give
/// identical bytes; `out` written atomically. "" or the reason.
std::string writeCanonicalPng(const std::filesystem::path& in, const std::filesystem::path& out);

/// Decodes a whole PNG a row at a time and keeps nothing: "" when it is
/// whole, else why not (a truncated or damaged file), quietly. For readers
/// that would print libpng's own messages on a damaged file (OpenImageIO's).
std::string checkPng(const std::filesystem::path& path);

}  // namespace relief
