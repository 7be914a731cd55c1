#pragma once
// The readers take a path: each fuzz input is written to a file of this
// process's own (in /dev/shm when there is one: memory, not disk) and read
// from there, exactly as relief reads a user's file.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/diagnostics.h"

namespace relief::fuzz {

inline std::filesystem::path inputFile(const char* extension) {
    const std::filesystem::path dir = std::filesystem::exists("/dev/shm") ? "/dev/shm" : "/tmp";
    return dir / ("relief-fuzz-" + std::to_string(::getpid()) + extension);
}

inline const std::filesystem::path& write(const std::uint8_t* data, std::size_t size, const char* extension) {
    static const std::filesystem::path path = inputFile(extension);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    return path;
}

// Every message formatted, as the command line prints them.
inline void format(const Diagnostics& diags) {
    for (const auto& d : diags.all()) (void)formatDiagnostic(d);
}

}  // namespace relief::fuzz
