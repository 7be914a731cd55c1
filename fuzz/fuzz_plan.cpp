// The render plan's reader (plan/plan.h) on arbitrary bytes as a plan's plan.json: whatever the
// file says, the reader ends, and a plan it accepts names only files inside its own folder and a
// still's sizes. The plan is what a Slurm task on another machine reads: untrusted input.
#include <cstdio>
#include <filesystem>

#include "fuzz/fuzz_input.h"
#include "plan/plan.h"

namespace {

bool plainName(const std::string& name) {
    return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::filesystem::path dir = [] {
        const auto d = relief::fuzz::inputFile(".plan");
        std::filesystem::create_directories(d);
        return d;
    }();
    if (std::FILE* f = std::fopen((dir / "plan.json").c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    relief::Diagnostics diags;
    const auto plan = relief::plan::readPlan(dir, diags);
    relief::fuzz::format(diags);
    if (plan) {
        if (plan->width < 1 || plan->height < 1 || plan->tiles < 1 || plan->tiles > plan->height) __builtin_trap();
        if (!plainName(plan->pov.name)) __builtin_trap();
        for (const auto& f : plan->reads)
            if (!plainName(f.name)) __builtin_trap();
        (void)relief::plan::missingTiles(*plan);
    }
    return 0;
}
