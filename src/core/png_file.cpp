#include "core/png_file.h"

#include <OpenImageIO/imageio.h>

#include "core/atomic_file.h"

namespace relief {

std::string writePngAtomically(const std::filesystem::path& path, const PngPixels& pixels) {
    const OIIO::TypeDesc type = pixels.sixteenBit ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(pixels.width, pixels.height, pixels.channels, type);
    if (pixels.compression >= 0) spec.attribute("png:compressionLevel", pixels.compression);
    return writeThroughTemporary(path, [&](const std::filesystem::path& temp) {
        auto output = OIIO::ImageOutput::create(temp.string());
        if (!output || !output->open(temp.string(), spec) || !output->write_image(type, pixels.data) ||
            !output->close())
            return output ? output->geterror() : OIIO::geterror();
        return std::string();
    });
}

}  // namespace relief
