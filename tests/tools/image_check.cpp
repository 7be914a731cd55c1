// Golden-image check: compares a new render with every reference in a
// folder and passes when any of them matches within the thresholds
// (idiff's meaning). With RELIEF_UPDATE_GOLDEN=1 a failing render is copied
// into the folder as a new reference, to be reviewed in git.
// Usage: image_check NEW.png REF_DIR
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "compare/compare_images.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: image_check NEW.png REF_DIR\n";
        return 2;
    }
    const fs::path image = argv[1], refDir = argv[2];
    // Thresholds (fraction of full scale per channel): renders of the same
    // .pov by POV-Ray 3.7 are pixel-identical across runs and thread counts,
    // so any difference comes from a change upstream. 0.004 is one 8-bit step,
    // 0.02 % of pixels is ~4 pixels of a 160x120 still; 0.012 caps any pixel
    // at three steps, so a moved edge or a colour change fails.
    relief::compare::Thresholds t;
    t.fail = t.warn = 0.004;
    t.failPercent = 0.02;
    t.hardFail = 0.012;
    bool any = false;
    for (const auto& entry : fs::directory_iterator(refDir)) {
        if (entry.path().extension() != ".png") continue;
        any = true;
        const auto d = relief::compare::compareImages(image, entry.path(), t);
        if (d.verdict == relief::compare::Verdict::NotComparable || d.verdict == relief::compare::Verdict::FileError) {
            std::cout << entry.path().filename().string() << ": not comparable: " << d.error << '\n';
            continue;
        }
        std::cout << fmt::format("{}: max error {:.5f} at ({}, {}), mean {:.6f}, {} pixels "
                                 "({:.3f} %) over {} -> {}\n",
                                 entry.path().filename().string(), d.maxError, d.maxX, d.maxY,
                                 d.meanError, d.failingPixels, d.failingPercent, t.fail,
                                 relief::compare::verdictName(d.verdict));
        if (d.pass()) return 0;
    }
    if (!any) std::cout << "no reference image in " << refDir.string() << '\n';
    const char* update = std::getenv("RELIEF_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        int n = 0;
        fs::path dest;
        do dest = refDir / fmt::format("ref{}.png", n++);
        while (fs::exists(dest));
        fs::copy_file(image, dest);
        std::cout << "blessed " << dest.string() << " (review it in git)\n";
        return 0;
    }
    return 1;
}
