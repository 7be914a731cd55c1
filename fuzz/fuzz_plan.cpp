// The render plan's reader (plan/plan.h) on arbitrary bytes as a plan's plan.json: whatever the
// file says, the reader ends, and a plan it accepts names only files inside its own folder, a
// still's sizes and outputs beside the folder. The plan is what a Slurm task on another machine
// reads: untrusted input, verified whole (its hash, each file's SHA-256) before it is used.
// Each input is read twice: as it is (the hash check turns away nearly every mutation), and with
// its "hash" made right for its fields, as a forger who can write the folder would make it, so
// that the checks behind the hash see the mutations too. The folder holds one file, scene.pov
// (kPov below), which the seeds name with its SHA-256.
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz/fuzz_input.h"
#include "plan/plan.h"

namespace {

namespace fs = std::filesystem;

constexpr const char* kPov = "// the .pov of the fuzz target's plan\n";

void writeFile(const fs::path& path, const void* data, std::size_t size) {
    if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
}

bool plainName(const std::string& name) {
    return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos;
}

void readAndCheck(const fs::path& dir) {
    relief::Diagnostics diags;
    const auto plan = relief::plan::readPlan(dir, diags);
    relief::fuzz::format(diags);
    if (!plan) return;
    if (plan->width < 16 || plan->height < 16 || plan->tiles < 1 || plan->tiles > plan->height) __builtin_trap();
    if (!plainName(plan->pov.name)) __builtin_trap();
    for (const auto* files : {&plan->reads, &plan->extras, &plan->templates})
        for (const auto& f : *files)
            if (!plainName(f.name)) __builtin_trap();
    for (const auto& out : {plan->still, plan->sidecar, plan->pov.final})
        if (out.parent_path() != plan->dir.parent_path()) __builtin_trap();
    (void)relief::plan::missingTiles(*plan);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const fs::path dir = [] {
        const auto d = relief::fuzz::inputFile(".plan");
        fs::create_directories(d);
        const std::string pov = kPov;
        writeFile(d / "scene.pov", pov.data(), pov.size());
        return d;
    }();
    writeFile(dir / "plan.json", data, size);
    readAndCheck(dir);
    auto j = nlohmann::ordered_json::parse(data, data + size, nullptr, false);
    if (!j.is_object() || !j.contains("hash")) return 0;
    j.erase("hash");
    const std::string hash = relief::plan::planFieldsHash(j);
    j["hash"] = hash;
    const std::string forged = j.dump(1, ' ', false, nlohmann::json::error_handler_t::replace);
    writeFile(dir / "plan.json", forged.data(), forged.size());
    readAndCheck(dir);
    return 0;
}
