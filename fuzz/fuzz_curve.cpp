// The curve-file reader (JSON) on arbitrary bytes.
#include "curves/curve_file.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    relief::Diagnostics diags;
    (void)relief::curves::readCurveFile(relief::fuzz::write(data, size, ".json"), diags);
    relief::fuzz::format(diags);
    return 0;
}
