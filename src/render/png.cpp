#include "render/png.h"

#include <unistd.h>

#include <vector>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "core/atomic_file.h"

namespace relief::render {

std::string writeCanonicalPng(const std::filesystem::path& in, const std::filesystem::path& out) {
    auto input = OIIO::ImageInput::open(in.string());
    if (!input) return fmt::format("cannot read {}: {}", in.string(), OIIO::geterror());
    const OIIO::ImageSpec& src = input->spec();
    std::vector<unsigned char> pixels(src.image_bytes());
    if (!input->read_image(0, 0, 0, src.nchannels, OIIO::TypeDesc::UINT8, pixels.data()))
        return fmt::format("cannot read {}: {}", in.string(), input->geterror());
    OIIO::ImageSpec spec(src.width, src.height, src.nchannels, OIIO::TypeDesc::UINT8);
    input->close();

    return writeThroughTemporary(out, [&](const std::filesystem::path& temp) {
        auto output = OIIO::ImageOutput::create(temp.string());
        if (!output || !output->open(temp.string(), spec) ||
            !output->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !output->close())
            return output ? output->geterror() : OIIO::geterror();
        return std::string();
    });
}

}  // namespace relief::render
