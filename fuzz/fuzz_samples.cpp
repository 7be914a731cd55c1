// The CSV reader on arbitrary bytes: header, fields, numbers, ranges, duplicates, messages.
#include "fuzz/fuzz_input.h"
#include "geo/samples.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    relief::Diagnostics diags;
    const auto path = relief::fuzz::write(data, size, ".csv");
    (void)relief::geo::readSamples(path, "samples.csv", diags);
    relief::fuzz::format(diags);
    return 0;
}
