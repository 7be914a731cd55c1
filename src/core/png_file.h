#pragma once
// Writing a PNG whole or not at all: pixels only (no date or software
// chunks), so the same pixels give the same bytes, through a temporary file
// renamed into place.
#include <cstdint>
#include <filesystem>
#include <string>

namespace relief {

struct PngPixels {
    int width = 0, height = 0, channels = 1;
    bool sixteenBit = false;     ///< 16-bit samples (else 8-bit)
    const void* data = nullptr;  ///< rows top first, channels interleaved
    int compression = -1;        ///< zlib level 0..9; -1: the library's default
};

/// Returns "" or the error, naming `path`.
std::string writePngAtomically(const std::filesystem::path& path, const PngPixels& pixels);

}  // namespace relief
