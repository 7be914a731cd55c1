#include "core/png_file.h"

#include <cerrno>
#include <csetjmp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include <fmt/format.h>
#include <png.h>

#include "core/atomic_file.h"

namespace relief {

namespace {

// libpng reports errors through a callback that must not return: it records
// the message and long-jumps back to the setjmp in encode()/decode(). Those
// functions keep every object with a destructor outside the jump's reach.
[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
    if (auto* error = static_cast<std::string*>(png_get_error_ptr(png)); error && error->empty()) *error = message;
    png_longjmp(png, 1);
}

// libpng's own writer says only "Write Error": this one keeps the system's
// reason (a full disk) for the message.
[[noreturn]] void onWriteFailure(png_structp png, int err) {
    if (auto* error = static_cast<std::string*>(png_get_error_ptr(png)))
        *error = err ? writeFailureReason(err) : "write error";
    png_error(png, "write error");
}

void writeToFile(png_structp png, png_bytep data, png_size_t size) {
    if (std::fwrite(data, 1, size, static_cast<std::FILE*>(png_get_io_ptr(png))) != size) onWriteFailure(png, errno);
}

// A flush that fails is a write that failed: the stream drops what it could
// not write, and a later flush, with nothing left to write, would tell no
// reason ("Input/output error" for a full disk).
void flushFile(png_structp png) {
    if (std::fflush(static_cast<std::FILE*>(png_get_io_ptr(png))) != 0) onWriteFailure(png, errno);
}

void onPngWarning(png_structp, png_const_charp) {}

int colourType(int channels) {
    switch (channels) {
        case 1: return PNG_COLOR_TYPE_GRAY;
        case 2: return PNG_COLOR_TYPE_GRAY_ALPHA;
        case 3: return PNG_COLOR_TYPE_RGB;
        default: return PNG_COLOR_TYPE_RGB_ALPHA;
    }
}

bool encode(std::FILE* file, const PngPixels& p, png_bytep* rows, std::string& error) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, file, writeToFile, flushFile);
    if (p.compression >= 0) png_set_compression_level(png, p.compression);
    if (p.compression == 0) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);  // nothing to compress for
    png_set_IHDR(png, info, png_uint_32(p.width), png_uint_32(p.height), p.sixteenBit ? 16 : 8,
                 colourType(p.channels), PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (p.dpi > 0) {
        const auto perMetre = static_cast<png_uint_32>(std::lround(p.dpi / 0.0254));
        png_set_pHYs(png, info, perMetre, perMetre, PNG_RESOLUTION_METER);
    }
    png_write_info(png, info);
    if (p.sixteenBit) png_set_swap(png);  // PNG stores 16-bit samples big-endian
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

bool decode(std::FILE* file, PngImage8& image, std::vector<png_bytep>& rows, const PngSize* expected,
            std::string& error) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_init_io(png, file);
    png_read_info(png, info);
    // Nothing is allocated for a size the caller did not expect (a header can claim 60000 x 60000).
    if (expected && (png_get_image_width(png, info) != png_uint_32(expected->width) ||
                     png_get_image_height(png, info) != png_uint_32(expected->height))) {
        error = fmt::format("it is {} x {} pixels, not {} x {}", png_get_image_width(png, info),
                            png_get_image_height(png, info), expected->width, expected->height);
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_set_expand(png);  // palette -> RGB, grey < 8 bits -> 8 bits, tRNS -> alpha
    png_set_scale_16(png);
    png_read_update_info(png, info);
    image.width = int(png_get_image_width(png, info));
    image.height = int(png_get_image_height(png, info));
    image.channels = int(png_get_channels(png, info));
    const size_t rowBytes = png_get_rowbytes(png, info);
    image.pixels.resize(rowBytes * size_t(image.height));
    rows.resize(size_t(image.height));
    for (size_t y = 0; y < rows.size(); ++y) rows[y] = image.pixels.data() + y * rowBytes;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

bool decodeRows(std::FILE* file, std::vector<png_byte>& row, std::string& error) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_init_io(png, file);
    png_read_info(png, info);
    const int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    row.resize(png_get_rowbytes(png, info));
    const png_uint_32 height = png_get_image_height(png, info);
    for (int pass = 0; pass < passes; ++pass)
        for (png_uint_32 y = 0; y < height; ++y) png_read_row(png, row.data(), nullptr);
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

}  // namespace

std::string checkPng(const std::filesystem::path& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rbe"), std::fclose);
    if (!file) return "it cannot be opened";
    std::vector<png_byte> row;
    std::string error;
    if (!decodeRows(file.get(), row, error)) return error.empty() ? "libpng failed" : error;
    return "";
}

void writePngAtomically(const std::filesystem::path& path, const PngPixels& p) {
    if (p.width <= 0 || p.height <= 0 || p.channels < 1 || p.channels > 4 || !p.data)
        throw OutputError(shownPath(path), "cannot be written: no pixels");
    const size_t rowBytes = size_t(p.width) * size_t(p.channels) * (p.sixteenBit ? 2 : 1);
    std::vector<png_bytep> rows(size_t(p.height));
    for (size_t y = 0; y < rows.size(); ++y)
        rows[y] = const_cast<png_bytep>(static_cast<const png_byte*>(p.data) + y * rowBytes);
    AtomicFile out(path);
    std::string error;
    if (!encode(out.stream(), p, rows.data(), error))
        throw OutputError(shownPath(path), "cannot be written: " + (error.empty() ? "libpng failed" : error));
    out.commit();
}

std::string readPng8(const std::filesystem::path& path, PngImage8& image, const PngSize* expected) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rbe"), std::fclose);
    if (!file) return fmt::format("cannot read {}: cannot open it", path.string());
    png_byte signature[8] = {};
    if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
        return fmt::format("cannot read {}: not a PNG file", path.string());
    std::rewind(file.get());
    std::vector<png_bytep> rows;
    std::string error;
    if (!decode(file.get(), image, rows, expected, error))
        return fmt::format("cannot read {}: {}", path.string(), error.empty() ? "libpng failed" : error);
    return {};
}

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

}  // namespace relief
