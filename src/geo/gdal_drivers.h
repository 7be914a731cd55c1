#pragma once
// GDAL's drivers, registered once for the whole process.
#include <gdal.h>

namespace relief::geo {

/// GDALAllRegister, once: it is not safe to call from two threads at once, and
/// `relief test` runs its cases in parallel (a static local is initialised once).
inline void registerGdalDrivers() {
    static const bool registered = (GDALAllRegister(), true);
    (void)registered;
}

}  // namespace relief::geo
