#include "render/png.h"

#include <unistd.h>

#include <vector>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "core/png_file.h"

namespace relief::render {

std::string writeCanonicalPng(const std::filesystem::path& in, const std::filesystem::path& out) {
    auto input = OIIO::ImageInput::open(in.string());
    if (!input) return fmt::format("cannot read {}: {}", in.string(), OIIO::geterror());
    const OIIO::ImageSpec& src = input->spec();
    std::vector<unsigned char> pixels(src.image_bytes());
    if (!input->read_image(0, 0, 0, src.nchannels, OIIO::TypeDesc::UINT8, pixels.data()))
        return fmt::format("cannot read {}: {}", in.string(), input->geterror());
    input->close();
    return writePngAtomically(out, {src.width, src.height, src.nchannels, false, pixels.data()});
}

}  // namespace relief::render
