// The test-manifest reader (relief test) on arbitrary bytes.
#include "fuzz/fuzz_input.h"
#include "regress/regress.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    relief::Diagnostics diags;
    (void)relief::regress::readManifest(relief::fuzz::write(data, size, ".toml"), diags);
    relief::fuzz::format(diags);
    return 0;
}
