#pragma once
// The preview page's files, built into relief (web/: the page's own
// index.html, and preview.js with three.js bundled in by esbuild at build
// time from the lock file's versions), so that relief serves them from no
// folder anyone could change or link elsewhere.
#include <span>
#include <string_view>

namespace relief::serve {

struct WebAsset {
    std::string_view name;         ///< as the page asks for it: "" (the page), "preview.js"
    std::string_view contentType;
    std::string_view bytes;
};
std::span<const WebAsset> webAssets();

}  // namespace relief::serve
