#pragma once
// The constants every module uses, defined once.

namespace conform {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

// The largest magnitude of a number a job reads from a table (a coordinate or length in mm: 10 km; an angle in
// degrees; a time in s): anything larger is a broken file, refused where it is read (csv.h), not computed with
// (a 1e300 coordinate printed 300 digits into a robot program).
inline constexpr double kMaxMagnitude = 1e7;
// The largest radius of a cylinder, pipe or tube a job takes, mm (1 km).
inline constexpr double kMaxRadiusMm = 1e6;

}  // namespace conform
