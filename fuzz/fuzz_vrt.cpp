// relief's check of a scene's VRT (geo/gdal_setup.h) on arbitrary bytes, as GDAL would be asked
// to open them: whatever the XML says, the check ends, and says why a VRT is refused.
#include "fuzz/fuzz_input.h"
#include "geo/gdal_setup.h"
#include "geo/raster.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = relief::fuzz::write(data, size, ".vrt");
    (void)relief::geo::gdalInputProblem(path);
    (void)relief::geo::isRasterDem(path);
    return 0;
}
