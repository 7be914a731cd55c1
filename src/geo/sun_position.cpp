#include "geo/sun_position.h"

#include <cmath>

#include <libnova/precession.h>
#include <libnova/refraction.h>
#include <libnova/solar.h>
#include <libnova/transform.h>

namespace relief::geo {

SunPosition sunPosition(double lonDeg, double latDeg, std::int64_t utcSeconds) {
    // Julian day of the Unix epoch. UT stands in for TT in the ephemeris: the
    // 69 s between them move the sun by 0.001 degrees.
    const double jd = 2440587.5 + static_cast<double>(utcSeconds) / 86400.0;
    // libnova gives the sun's place referred to the J2000 equinox; the hour
    // angle needs the equinox of the date (50 arcseconds a year apart: a third
    // of a degree of azimuth by 2022 without this step).
    constexpr double kJ2000 = 2451545.0;
    ln_equ_posn j2000{}, equatorial{};
    ln_get_solar_equ_coords(jd, &j2000);
    ln_get_equ_prec2(&j2000, kJ2000, jd, &equatorial);
    ln_lnlat_posn observer{lonDeg, latDeg};
    ln_hrz_posn horizontal{};
    ln_get_hrz_from_equ(&equatorial, &observer, jd, &horizontal);
    SunPosition sun;
    // libnova measures azimuth from the south, westwards.
    sun.azimuthDeg = std::fmod(horizontal.az + 180.0, 360.0);
    if (sun.azimuthDeg < 0) sun.azimuthDeg += 360.0;
    sun.trueAltitudeDeg = horizontal.alt;
    // Refraction lifts the sun near the horizon (34 arcminutes at it); below
    // a degree under it the formula means nothing and the sun is set anyway.
    sun.altitudeDeg = horizontal.alt > -1.0 ? horizontal.alt + ln_get_refraction_adj(horizontal.alt, 1010, 10)
                                            : horizontal.alt;
    return sun;
}

}  // namespace relief::geo
