#pragma once
// An independent reference for the sun's place: the equations of NOAA's
// solar calculator as NOAA publishes them (the "NOAA Solar Calculations"
// spreadsheets of the Global Monitoring Laboratory, after Meeus,
// "Astronomical Algorithms"), written here column by column from that
// published list, not from libnova: geometric mean longitude and anomaly, the
// equation of centre, apparent longitude, corrected obliquity, declination,
// the equation of time, true solar time, hour angle, zenith, NOAA's own
// refraction approximation, and azimuth clockwise from north. NOAA gives it
// as accurate to about 0.01 degrees between 1800 and 2100 away from the poles.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace relief::reference {

struct NoaaSun {
    double azimuthDeg, elevationDeg;  ///< elevation corrected for refraction, as the calculator shows it
};

inline NoaaSun noaaSun(double lonDeg, double latDeg, std::int64_t utcSeconds) {
    constexpr double kPi = 3.14159265358979323846;
    const auto rad = [](double d) { return d * kPi / 180; };
    const auto deg = [](double r) { return r * 180 / kPi; };
    const auto mod = [](double a, double n) { return a - n * std::floor(a / n); };
    const double jd = 2440587.5 + utcSeconds / 86400.0;
    const double jc = (jd - 2451545) / 36525;
    const double l0 = mod(280.46646 + jc * (36000.76983 + jc * 0.0003032), 360);
    const double m = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);
    const double e = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);
    const double c = std::sin(rad(m)) * (1.914602 - jc * (0.004817 + 0.000014 * jc)) +
                     std::sin(rad(2 * m)) * (0.019993 - 0.000101 * jc) + std::sin(rad(3 * m)) * 0.000289;
    const double trueLong = l0 + c;
    const double appLong = trueLong - 0.00569 - 0.00478 * std::sin(rad(125.04 - 1934.136 * jc));
    const double meanObliq = 23 + (26 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60) / 60;
    const double obliq = meanObliq + 0.00256 * std::cos(rad(125.04 - 1934.136 * jc));
    const double decl = deg(std::asin(std::sin(rad(obliq)) * std::sin(rad(appLong))));
    const double y = std::pow(std::tan(rad(obliq / 2)), 2);
    const double eqTimeMin =
        4 * deg(y * std::sin(2 * rad(l0)) - 2 * e * std::sin(rad(m)) +
                4 * e * y * std::sin(rad(m)) * std::cos(2 * rad(l0)) - 0.5 * y * y * std::sin(4 * rad(l0)) -
                1.25 * e * e * std::sin(2 * rad(m)));
    const double minutesUtc = mod(static_cast<double>(utcSeconds), 86400) / 60;
    const double trueSolarMin = mod(minutesUtc + eqTimeMin + 4 * lonDeg, 1440);
    const double hourAngle = trueSolarMin / 4 < 0 ? trueSolarMin / 4 + 180 : trueSolarMin / 4 - 180;
    const double zenith = deg(std::acos(std::sin(rad(latDeg)) * std::sin(rad(decl)) +
                                        std::cos(rad(latDeg)) * std::cos(rad(decl)) * std::cos(rad(hourAngle))));
    const double elev = 90 - zenith;
    double refractionArcsec = 0;
    const double t = std::tan(rad(elev));
    if (elev > 85) refractionArcsec = 0;
    else if (elev > 5) refractionArcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5);
    else if (elev > -0.575) refractionArcsec = 1735 + elev * (-518.2 + elev * (103.4 + elev * (-12.79 + elev * 0.711)));
    else refractionArcsec = -20.772 / t;
    const double a = deg(std::acos(std::clamp(
        (std::sin(rad(latDeg)) * std::cos(rad(zenith)) - std::sin(rad(decl))) /
            (std::cos(rad(latDeg)) * std::sin(rad(zenith))),
        -1.0, 1.0)));
    const double azimuth = hourAngle > 0 ? mod(a + 180, 360) : mod(540 - a, 360);
    return {azimuth, elev + refractionArcsec / 3600};
}

}  // namespace relief::reference
