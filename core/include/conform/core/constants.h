#pragma once
// The constants every module uses, defined once.

#include <limits>

namespace conform {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr double kHalfPi = kPi / 2.0;
// Degrees in a radian: an angle in radians times this is in degrees.
inline constexpr double kDegPerRad = 180.0 / kPi;
// An angle in degrees (a CLI flag, a JSON key ending in _deg) in radians, as the API takes it.
inline constexpr double radians(double deg) { return deg / 180.0 * kPi; }
// An angle in radians in degrees, as the CLI and the JSON give it.
inline constexpr double degrees(double rad) { return rad / kPi * 180.0; }
// The value of a figure that could not be computed (no points, no surface in reach).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The largest magnitude of a number a job reads from a table (a coordinate or length in mm: 10 km; an angle in
// degrees; a time in s): anything larger is a broken file, refused where it is read (csv.h), not computed with
// (a 1e300 coordinate printed 300 digits into a robot program).
inline constexpr double kMaxMagnitude = 1e7;
// The largest radius of a cylinder, pipe or tube a job takes, mm (1 km).
inline constexpr double kMaxRadiusMm = 1e6;

}  // namespace conform
