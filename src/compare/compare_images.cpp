#include "compare/compare_images.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/png_file.h"
#include "core/memory_budget.h"

namespace relief::compare {

const char* verdictName(Verdict v) {
    switch (v) {
        case Verdict::Pass: return "PASS";
        case Verdict::Warning: return "WARNING";
        case Verdict::Failure: return "FAILURE";
        case Verdict::NotComparable: return "NOT COMPARABLE";
        case Verdict::FileError: return "FILE ERROR";
    }
    return "?";
}

namespace {

// What comparing two images and making their difference image takes, a
// pixel: both images as stored, their difference in floats (every channel),
// its largest channel and that scaled, the heat map (three floats) and its
// 8-bit copy as written.
double bytesPerComparedPixel(int channels, size_t sampleBytes) {
    return 2.0 * channels * double(sampleBytes) + 4.0 * channels + 4 + 4 + 12 + 3;
}

// What an image's header says, before anything is decoded.
struct ImageHeader {
    int width = 0, height = 0, channels = 1;
    size_t sampleBytes = 1;
    double pixels = 0;
    std::string format;
};

std::optional<ImageHeader> headerOf(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        (void)OIIO::geterror();  // OpenImageIO's own message names no more than we do
        return std::nullopt;
    }
    const OIIO::ImageSpec& spec = in->spec();
    ImageHeader h{spec.width, spec.height, std::max(1, spec.nchannels), std::max<size_t>(1, spec.format.size()),
                  double(spec.width) * double(spec.height) * std::max(1, spec.depth), in->format_name()};
    in->close();
    return h;
}

// The size a header says, held against what can be decoded, before anything
// is allocated for it: for a PNG, what its bytes can hold (deflate compresses
// at most 1032:1: a 177-byte file claiming 12000 x 12000 pixels is damaged);
// the pixel limit (a 140 kB PNG of 12000 x 12000 zeros is not damaged, but a
// bomb); the memory budget for its channels.
std::string headerProblem(const ImageHeader& h, std::uintmax_t fileBytes) {
    if (!(h.pixels > 0)) return "the image has no pixels";
    if (h.format == "png" && h.pixels * h.channels * double(h.sampleBytes) > 1032.0 * double(fileBytes) + 65536)
        return fmt::format("it says it is {} x {} pixels, more than its {} can hold: the file is damaged", h.width,
                           h.height, byteSize(fileBytes));
    if (h.pixels > kMaxComparedPixels)
        return fmt::format("it says it is {} x {} pixels ({:.0f} Mpixels), more than the {:.0f} Mpixels relief "
                           "compares: compare smaller images, or crops of these",
                           h.width, h.height, h.pixels / 1e6, kMaxComparedPixels / 1e6);
    const double budgetMB = defaultMemoryBudgetMB();
    const double neededMB = h.pixels * bytesPerComparedPixel(h.channels, h.sampleBytes) / 1e6;
    if (neededMB > budgetMB)
        return fmt::format("it says it is {} x {} pixels with {} channels: comparing two such images and making their "
                           "difference image needs about {:.0f} MB, more than the {:.0f} MB relief may use",
                           h.width, h.height, h.channels, neededMB, budgetMB);
    return "";
}

std::string sizeProblem(const std::filesystem::path& path, std::uintmax_t fileBytes) {
    const auto header = headerOf(path);
    if (!header) return "cannot read as an image (not a format OpenImageIO reads, or damaged)";
    if (std::string problem = headerProblem(*header, fileBytes); !problem.empty()) return problem;
    // OpenImageIO lets libpng print its own messages on a damaged PNG: found first, quietly.
    if (header->format == "png")
        if (const std::string problem = checkPng(path); !problem.empty())
            return fmt::format("it is a damaged or truncated PNG ({})", problem);
    return "";
}

bool readImage(const std::filesystem::path& path, OIIO::ImageBuf& buf, std::string& error) {
    std::error_code ec;
    if (std::string problem = inputFileProblem(path); !problem.empty()) {
        error = fmt::format("{}: {}", path.string(), problem);
        return false;
    }
    if (std::string problem = sizeProblem(path, std::filesystem::file_size(path, ec)); !problem.empty()) {
        error = fmt::format("{}: {}", path.string(), problem);
        return false;
    }
    buf.reset(path.string());
    if (!buf.read(0, 0, true)) {  // native pixel type: no float copy of the image
        (void)buf.geterror();
        error = fmt::format("{}: cannot read as an image (damaged or truncated)", path.string());
        return false;
    }
    return true;
}

}  // namespace

ImageDifference compareImages(const std::filesystem::path& a, const std::filesystem::path& b,
                              const Thresholds& t) {
    ImageDifference d;
    OIIO::ImageBuf A, B;
    if (!readImage(a, A, d.error) || !readImage(b, B, d.error)) {
        d.verdict = Verdict::FileError;
        return d;
    }
    const auto& sa = A.spec();
    const auto& sb = B.spec();
    if (sa.width != sb.width || sa.height != sb.height || sa.nchannels != sb.nchannels) {
        d.verdict = Verdict::NotComparable;
        d.error = fmt::format("not comparable: {} is {} x {} with {} channels, {} is {} x {} with "
                              "{} channels",
                              a.string(), sa.width, sa.height, sa.nchannels, b.string(), sb.width,
                              sb.height, sb.nchannels);
        return d;
    }
    d.width = sa.width;
    d.height = sa.height;
    d.channels = sa.nchannels;
    const double pixels = static_cast<double>(sa.width) * sa.height;

    const auto all = OIIO::ImageBufAlgo::compare(A, B, static_cast<float>(t.fail),
                                                 static_cast<float>(t.warn));
    d.maxError = all.maxerror;
    d.maxX = all.maxx;
    d.maxY = all.maxy;
    d.maxChannel = all.maxc;
    d.meanError = all.meanerror;
    d.rmsError = all.rms_error;
    d.psnr = all.PSNR;
    d.failingPixels = static_cast<long long>(all.nfail);
    d.warningPixels = static_cast<long long>(all.nwarn);
    d.failingPercent = 100.0 * static_cast<double>(d.failingPixels) / pixels;
    d.warningPercent = 100.0 * static_cast<double>(d.warningPixels) / pixels;
    if (t.hardFail < 1e300) {
        const auto hard = OIIO::ImageBufAlgo::compare(A, B, static_cast<float>(t.hardFail),
                                                      static_cast<float>(t.hardFail));
        d.hardFailingPixels = static_cast<long long>(hard.nfail);
    }
    for (int c = 0; c < sa.nchannels; ++c) {
        OIIO::ROI roi = A.roi();
        roi.chbegin = c;
        roi.chend = c + 1;
        const auto r = OIIO::ImageBufAlgo::compare(A, B, static_cast<float>(t.fail),
                                                   static_cast<float>(t.warn), roi);
        const std::string name = c < static_cast<int>(sa.channelnames.size())
                                     ? sa.channelnames[c]
                                     : fmt::format("channel {}", c);
        d.perChannel.push_back({name, r.maxerror, r.maxx, r.maxy, r.meanerror, r.rms_error, r.PSNR});
    }
    d.constantA = OIIO::ImageBufAlgo::isConstantColor(A);
    d.constantB = OIIO::ImageBufAlgo::isConstantColor(B);

    // idiff's rules; --allowfailures lets that many pixels fail by any amount.
    const double failLimit = std::max(t.failPercent / 100.0 * pixels, static_cast<double>(t.allowFailures));
    const bool hardFail = d.maxError > t.hardFail && d.hardFailingPixels > t.allowFailures;
    if (static_cast<double>(d.failingPixels) > failLimit || hardFail)
        d.verdict = Verdict::Failure;
    else if (static_cast<double>(d.warningPixels) >
                 std::max(t.warnPercent / 100.0 * pixels, static_cast<double>(t.allowFailures)) ||
             (d.maxError > t.hardWarn && d.warningPixels > t.allowFailures))
        d.verdict = Verdict::Warning;
    else
        d.verdict = Verdict::Pass;
    return d;
}

std::string writeDifferenceImage(const std::filesystem::path& a, const std::filesystem::path& b,
                                 const std::filesystem::path& out) {
    OIIO::ImageBuf A, B;
    std::string error;
    if (!readImage(a, A, error) || !readImage(b, B, error)) return error;
    if (A.spec().width != B.spec().width || A.spec().height != B.spec().height ||
        A.spec().nchannels != B.spec().nchannels)
        return "images of different sizes have no difference image";
    OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(A, B);
    OIIO::ImageBuf largest = OIIO::ImageBufAlgo::maxchan(diff);
    float maxValue = 0;
    {
        const auto stats = OIIO::ImageBufAlgo::computePixelStats(largest);
        maxValue = stats.max.empty() ? 0.f : stats.max[0];
    }
    if (maxValue > 0) largest = OIIO::ImageBufAlgo::mul(largest, 1.0f / maxValue);
    OIIO::ImageBuf heat = OIIO::ImageBufAlgo::color_map(largest, 0, "inferno");
    try {
        writeThroughTemporary(out, [&](const std::filesystem::path& temp) {
            return heat.write(temp.string(), OIIO::TypeDesc::UINT8) ? std::string() : heat.geterror();
        });
    } catch (const OutputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace relief::compare
