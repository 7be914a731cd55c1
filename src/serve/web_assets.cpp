#include "serve/web_assets.h"

// Each file's bytes in the executable's read-only data, between two symbols
// (the assembler's .incbin, which g++ and clang both take; the paths come from
// CMake: RELIEF_WEB_INDEX_HTML, RELIEF_WEB_PREVIEW_JS). This file is compiled
// alone (no unity build), so the macro reaches no other.
#define RELIEF_EMBED(symbol, file)                                                                  \
    asm(".section .rodata\n.balign 16\n.global " #symbol "_begin\n" #symbol "_begin:\n.incbin \"" file \
        "\"\n.global " #symbol "_end\n" #symbol "_end:\n.byte 0\n.previous\n");                     \
    extern "C" const char symbol##_begin[];                                                          \
    extern "C" const char symbol##_end[];

RELIEF_EMBED(relief_web_index_html, RELIEF_WEB_INDEX_HTML)
RELIEF_EMBED(relief_web_preview_js, RELIEF_WEB_PREVIEW_JS)
#undef RELIEF_EMBED

namespace relief::serve {

namespace {
std::string_view between(const char* begin, const char* end) {
    return {begin, static_cast<size_t>(end - begin)};
}
}  // namespace

std::span<const WebAsset> webAssets() {
    static const WebAsset assets[] = {
        {"", "text/html; charset=utf-8", between(relief_web_index_html_begin, relief_web_index_html_end)},
        // Not text/javascript: cpp-httplib compresses text/* (and bare application/javascript) with
        // Brotli at its highest quality when the browser accepts it, 2.5 s for this file, on
        // loopback where compression saves nothing. A module script may be any JavaScript type.
        {"preview.js", "application/javascript; charset=utf-8",
         between(relief_web_preview_js_begin, relief_web_preview_js_end)},
    };
    return assets;
}

}  // namespace relief::serve
