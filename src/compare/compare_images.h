#pragma once
// Image comparison with OpenImageIO's ImageBufAlgo::compare, for golden-image
// tests (and, later, `relief diff`). Thresholds have idiff's meaning.
#include <filesystem>
#include <string>

namespace relief::compare {

struct Thresholds {
    double fail = 0.004;         ///< a pixel fails when any channel differs by more
    double failPercent = 0.02;   ///< the images fail when more than this % of pixels fail
    double hardFail = 0.012;     ///< any pixel over this fails the images
};

struct ImageDifference {
    bool comparable = false;  ///< same size and channel count, both readable
    std::string error;        ///< why not comparable
    double maxError = 0;      ///< largest channel difference, 0..1
    int maxX = 0, maxY = 0;   ///< where
    double meanError = 0;
    double rmsError = 0;
    double psnr = 0;
    long long failingPixels = 0;  ///< over `fail`
    double failingPercent = 0;
    bool pass = false;
};

ImageDifference compareImages(const std::filesystem::path& a, const std::filesystem::path& b,
                              const Thresholds& thresholds);

}  // namespace relief::compare
