#pragma once
// Options that take several numbers in one argument ("--bump 10,0,1.5,40", "--web-normal 0,0,1").

#include <cstddef>
#include <string>
#include <vector>

namespace conform::app {

// "1,2.5,-3" -> {1, 2.5, -3}: exactly `count` finite comma-separated numbers, or conform::Error naming the flag, the
// argument and the `shape` expected ("x,y,z", "AZ_DEG,Z_MM,HEIGHT_MM,RADIUS_MM").
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& flag,
                                  const std::string& shape);

}  // namespace conform::app
