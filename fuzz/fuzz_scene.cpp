// The scene reader on arbitrary bytes: TOML parsing, every key's checks, every message.
#include "fuzz/fuzz_input.h"
#include "scene/read_scene.h"
#include "subdiv/resolve.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    relief::Diagnostics diags;
    const auto scene = relief::scene::readScene(relief::fuzz::write(data, size, ".toml"), diags);
    if (scene && !diags.hasErrors()) (void)relief::subdiv::resolveScheme(scene->subdivision.scheme, diags);
    relief::fuzz::format(diags);
    return 0;
}
