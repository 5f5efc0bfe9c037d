#pragma once
// The units of a job's two inputs: --units sets both, --scan-units and --reference-units each override it for one
// (a scan in metres against CAD in millimetres is common). CAD keeps the units written in its file (cad_inputs.h).

#include <string>

#include <CLI/CLI.hpp>

namespace conform::app {

struct InputUnits {
  std::string both = "mm";
  std::string scan;       // empty: `both`
  std::string reference;  // empty: `both`

  const std::string& of_scan() const { return scan.empty() ? both : scan; }
  const std::string& of_reference() const { return reference.empty() ? both : reference; }
};

// --units (help: `both_help`), --scan-units, --reference-units.
void add_unit_options(CLI::App& command, InputUnits& units, const std::string& both_help);

}  // namespace conform::app
