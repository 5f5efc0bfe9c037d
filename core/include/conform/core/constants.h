#pragma once
// The constants every module uses, defined once.

namespace conform {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

}  // namespace conform
