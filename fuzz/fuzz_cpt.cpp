// The GMT colour palette reader (.cpt) on arbitrary bytes. What it returns
// must hold: at least two stops, bottom to top, finite, colours in 0..1.
#include <cmath>
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "scene/cpt_palette.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    relief::Diagnostics diags;
    const auto stops =
        relief::scene::parseCpt(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.cpt", diags);
    relief::fuzz::format(diags);
    if (stops) {
        if (stops->size() < 2 || diags.errorCount() > 0) __builtin_trap();
        for (size_t i = 0; i < stops->size(); ++i) {
            const auto& s = (*stops)[i];
            if (!std::isfinite(s.elevM) || (i > 0 && s.elevM < (*stops)[i - 1].elevM)) __builtin_trap();
            for (const double c : {s.rgb.r, s.rgb.g, s.rgb.b})
                if (!(c >= 0 && c <= 1)) __builtin_trap();
        }
    }
    return 0;
}
