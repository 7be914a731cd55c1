#include "compare/compare_images.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

namespace relief::compare {

ImageDifference compareImages(const std::filesystem::path& a, const std::filesystem::path& b,
                              const Thresholds& t) {
    ImageDifference d;
    OIIO::ImageBuf A(a.string()), B(b.string());
    if (!A.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
        d.error = fmt::format("cannot read {}: {}", a.string(), A.geterror());
        return d;
    }
    if (!B.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
        d.error = fmt::format("cannot read {}: {}", b.string(), B.geterror());
        return d;
    }
    const auto& sa = A.spec();
    const auto& sb = B.spec();
    if (sa.width != sb.width || sa.height != sb.height || sa.nchannels != sb.nchannels) {
        d.error = fmt::format("{} is {}x{}x{} but {} is {}x{}x{}", a.string(), sa.width,
                              sa.height, sa.nchannels, b.string(), sb.width, sb.height,
                              sb.nchannels);
        return d;
    }
    const auto r = OIIO::ImageBufAlgo::compare(A, B, t.fail, t.fail);
    d.comparable = true;
    d.maxError = r.maxerror;
    d.maxX = r.maxx;
    d.maxY = r.maxy;
    d.meanError = r.meanerror;
    d.rmsError = r.rms_error;
    d.psnr = r.PSNR;
    d.failingPixels = static_cast<long long>(r.nfail);
    d.failingPercent = 100.0 * static_cast<double>(r.nfail) /
                       (static_cast<double>(sa.width) * sa.height);
    d.pass = d.failingPercent <= t.failPercent && d.maxError <= t.hardFail;
    return d;
}

}  // namespace relief::compare
