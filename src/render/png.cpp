#include "render/png.h"

#include "core/output_set.h"
#include "core/png_file.h"

namespace relief::render {

std::string writeCanonicalPng(const std::filesystem::path& in, const std::filesystem::path& out) {
    PngImage8 image;
    if (std::string error = readPng8(in, image); !error.empty()) return error;
    try {
        writePngAtomically(out, {image.width, image.height, image.channels, false, image.pixels.data()});
    } catch (const OutputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace relief::render
