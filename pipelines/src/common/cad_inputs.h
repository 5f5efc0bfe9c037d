#pragma once
// How the jobs read a reference that may be CAD: the job's CadReadOptions into the reader's options, and the CAD
// report of each file read kept for the result.

#include <string>
#include <vector>

#include "conform/core/cad.h"
#include "conform/core/io.h"

namespace conform::detail {

inline ReadOptions read_options(NonFinitePolicy non_finite, const CadReadOptions& cad) {
  ReadOptions read;
  read.non_finite = non_finite;
  read.cad = cad;
  return read;
}

// Appends the report's CAD part when the file was CAD.
inline void keep_cad_report(const ReadReport& report, std::vector<CadReport>& out) {
  if (report.cad.read) out.push_back(report.cad);
}

// --units scales mesh and cloud files; a CAD file says its own unit and is in mm already. True (and a warning when
// the units asked for are not mm) when `path` is CAD and must not be scaled.
inline bool cad_keeps_its_units(const ReadReport& report, double mm_per_unit, std::vector<std::string>& warnings) {
  if (!report.cad.read) return false;
  if (mm_per_unit != 1.0) {
    warnings.push_back(report.cad.path + ": --units (--scan-units, --reference-units) does not apply to a CAD file; its own unit (" +
                       report.cad.file_unit + ") was converted to mm");
  }
  return true;
}

}  // namespace conform::detail
