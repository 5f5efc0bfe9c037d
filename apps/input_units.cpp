#include "input_units.h"

namespace conform::app {

void add_unit_options(CLI::App& command, InputUnits& units, const std::string& both_help) {
  command.add_option("--units", units.both, both_help);
  command.add_option("--scan-units", units.scan,
                     "Units of the scan alone (mm, cm, m, in), overriding --units for it");
  command.add_option("--reference-units", units.reference,
                     "Units of the reference alone (mm, cm, m, in), overriding --units for it; a CAD file keeps the "
                     "units written in it");
}

}  // namespace conform::app
