#pragma once
// Where the sun is in the sky at a place and an instant, for [lighting]
// datetime. The ephemeris is libnova's (Meeus, "Astronomical Algorithms":
// VSOP87 for the Earth, nutation and aberration); this file only converts
// conventions and adds the atmosphere's refraction.

#include <cstdint>

namespace relief::geo {

struct SunPosition {
    double azimuthDeg = 0;        ///< true bearing, clockwise from true north, [0, 360)
    double altitudeDeg = 0;       ///< apparent: above the horizon, refraction included
    double trueAltitudeDeg = 0;   ///< geometric, without the atmosphere
};

/// The sun seen from (lonDeg east, latDeg north) at `utcSeconds` after
/// 1970-01-01T00:00:00Z. Refraction is the standard atmosphere's (1010 hPa,
/// 10 °C), as the NOAA calculator reports it; the observer's height is not
/// used (a few arcseconds of parallax).
SunPosition sunPosition(double lonDeg, double latDeg, std::int64_t utcSeconds);

}  // namespace relief::geo
