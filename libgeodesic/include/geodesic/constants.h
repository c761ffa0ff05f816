#pragma once
// The constants that libgeodesic and libgeotri share, defined once.

namespace geotri::geodesic {

inline constexpr double k_pi = 3.14159265358979323846;
inline constexpr double k_two_pi = 2.0 * k_pi;
inline constexpr double k_degrees_per_radian = 180.0 / k_pi;

}  // namespace geotri::geodesic
