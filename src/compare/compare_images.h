#pragma once
// Image comparison with OpenImageIO's ImageBufAlgo, for `relief diff`,
// `relief test` and the golden-image tests. Thresholds and verdicts have
// idiff's meaning, except where idiff surprises: images of different sizes
// or channel counts are not comparable (idiff compares them against black),
// and a constant image on either side is reported.
#include <filesystem>
#include <string>
#include <vector>

namespace relief::compare {

/// The most pixels (width x height) an image relief compares may have, read
/// from its header before anything is decoded; the difference image has the
/// images' size, so one limit holds both. 40 Mpixels: an A2 page at 300 dpi
/// is 35. Comparing two RGBA images of that size and making their difference
/// image takes 1.2 GB (8 bits a channel) to 1.7 GB (16 bits), as measured at
/// 36 Mpixels; what the header's channels would take is held to the memory
/// budget as well.
inline constexpr double kMaxComparedPixels = 40e6;

struct Thresholds {
    double fail = 1e-6;          ///< a pixel fails when any channel differs by more
    double failPercent = 0;      ///< the images fail when more than this % of pixels fail
    double hardFail = 1e300;     ///< any pixel over this fails the images
    double warn = 1e-6;
    double warnPercent = 0;
    double hardWarn = 1e300;
    long long allowFailures = 0; ///< this many pixels may fail, by any amount
};

enum class Verdict { Pass = 0, Warning = 1, Failure = 2, NotComparable = 3, FileError = 4 };
const char* verdictName(Verdict v);  ///< "PASS", "WARNING", "FAILURE", ...

struct ChannelStats {
    std::string name;
    double maxError = 0;
    int maxX = 0, maxY = 0;
    double meanError = 0, rmsError = 0, psnr = 0;
};

struct ImageDifference {
    Verdict verdict = Verdict::FileError;
    std::string error;  ///< why not comparable / the file error
    int width = 0, height = 0, channels = 0;
    // Overall (all channels):
    double maxError = 0;
    int maxX = 0, maxY = 0, maxChannel = 0;
    double meanError = 0, rmsError = 0, psnr = 0;
    long long failingPixels = 0, warningPixels = 0, hardFailingPixels = 0;
    double failingPercent = 0, warningPercent = 0;
    std::vector<ChannelStats> perChannel;
    bool constantA = false, constantB = false;  ///< all pixels one colour
    bool pass() const { return verdict == Verdict::Pass || verdict == Verdict::Warning; }
};

/// Compares two images (every channel, as floats 0..1).
ImageDifference compareImages(const std::filesystem::path& a, const std::filesystem::path& b,
                              const Thresholds& thresholds);

/// Writes a heat map of max over channels of |A - B|, scaled so the largest
/// difference is the top of OpenImageIO's "inferno" map (identical: black).
/// Returns "" or the error.
std::string writeDifferenceImage(const std::filesystem::path& a, const std::filesystem::path& b,
                                 const std::filesystem::path& out);

}  // namespace relief::compare
