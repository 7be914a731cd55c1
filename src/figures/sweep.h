#pragma once
// `relief sweep`: one still per combination of parameter values, assembled
// into a labelled contact sheet (one PNG), like the parameter-influence
// figures of the source papers.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/diagnostics.h"

namespace relief::figures {

/// One --vary: a scene key and its values, as typed ("subdivision.omega", {"0.02", "1/32"}).
struct Variation {
    std::string key;
    std::vector<std::string> values;
};

struct Tile {
    std::filesystem::path image;
    std::string label;  ///< e.g. "omega = 0.02, lambda = 1/16"
};

/// Lays the tiles out in a grid (`columns`; 0 = the first variation's count),
/// each with its label under it, on white; writes `out` atomically. Labels use
/// the DejaVu Sans font (Debian fonts-dejavu-core). Returns "" or the error.
std::string writeContactSheet(const std::vector<Tile>& tiles, int columns, const std::string& title,
                              const std::filesystem::path& out);

/// Every combination of the variations' values, first variation fastest.
std::vector<std::vector<std::pair<std::string, std::string>>> combinations(
    const std::vector<Variation>& variations);

}  // namespace relief::figures
