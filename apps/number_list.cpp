#include "number_list.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "conform/core/error.h"

namespace conform::app {

std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& flag,
                                  const std::string& shape) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v)) {
      throw Error(flag + " " + text + ": '" + item + "' is not a number; expected " + shape);
    }
    values.push_back(v);
  }
  if (values.size() != count) {
    throw Error(flag + " " + text + ": expected " + std::to_string(count) + " comma-separated numbers, " + shape);
  }
  return values;
}

}  // namespace conform::app
