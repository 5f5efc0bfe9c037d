#pragma once
// Checks shared by the job report tests: every table cell tied to the page's JSON (Cell::json_pointer) shows that
// value (a number to its printed decimals, text as is), and the scene object of a name.

#include <cmath>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "conform/report/page.h"

namespace conform::test {

// The number of tied cells checked; fails the test for a pointer the JSON lacks or a value the cell does not show.
inline std::size_t expect_cells_show_the_json(const html::Page& page) {
  std::size_t checked = 0;
  for (const html::Section& section : page.sections) {
    for (const html::Table& table : section.tables) {
      for (const auto& row : table.rows) {
        for (const html::Cell& cell : row) {
          if (cell.json_pointer.empty()) continue;
          const nlohmann::json::json_pointer pointer(cell.json_pointer);
          if (!page.result.contains(pointer)) {
            ADD_FAILURE() << table.title << ": " << cell.json_pointer << " is not in the page's JSON";
            continue;
          }
          const nlohmann::json& value = page.result.at(pointer);
          ++checked;
          if (value.is_number()) {
            const std::size_t dot = cell.text.find('.');
            const std::size_t decimals = dot == std::string::npos ? 0 : cell.text.size() - dot - 1;
            const bool exponent = cell.text.find('e') != std::string::npos;
            const double shown = std::strtod(cell.text.c_str(), nullptr);
            const double v = value.get<double>();
            const double tolerance = exponent ? 1e-2 * std::abs(v) : 0.5 * std::pow(10.0, -double(decimals)) + 1e-12;
            EXPECT_NEAR(shown, v, tolerance) << table.title << ": " << cell.json_pointer;
          } else if (value.is_string()) {
            EXPECT_EQ(cell.text, value.get<std::string>()) << table.title << ": " << cell.json_pointer;
          }
        }
      }
    }
  }
  return checked;
}

// The object named `name`, or nullptr (with a failure).
inline const html::SceneObject* scene_object(const html::Page& page, const std::string& name) {
  for (const html::SceneObject& o : page.scene.objects()) {
    if (o.name == name) return &o;
  }
  ADD_FAILURE() << "no scene object " << name;
  return nullptr;
}

}  // namespace conform::test
