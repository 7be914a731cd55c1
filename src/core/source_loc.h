#pragma once
// Where a value came from: a scene file, a CSV file, a template. Carried in
// the IR so that later stages can still point at the offending line.
#include <string>

namespace relief {

struct SourceLoc {
    std::string file;  ///< path as the user gave it (empty: no file)
    int line = 0;      ///< 1-based; 0 when unknown
    int column = 0;    ///< 1-based; 0 when unknown
};

}  // namespace relief
