#pragma once
// `conform inspect --tolerances FILE.csv`: per face the limits of its deviation and of its form, and the verdict.
//
//   face,lower_mm,upper_mm,form_mm       (an empty cell: that figure is not toleranced)
//   3,-0.05,0.05,0.03
//
// A face passes its profile limits when every assigned point's deviation lies in [lower, upper] (ISO 1101's surface
// profile: the whole surface within the zone), and its form when form_mm (InspectOptions::form_trim) is at most the
// given width.

#include <string>
#include <vector>

#include "conform/pipelines/inspect/inspect.h"

namespace conform::detail {

// Reads the file and returns one FaceTolerance per row. Throws conform::Error naming the file and line: a missing
// column, a face id not in 1..face_count or given twice, a number that is not one, lower > upper, a form width <= 0, a
// row that tolerances nothing.
std::vector<FaceTolerance> read_face_tolerances(const std::string& path, std::size_t face_count);

// Judges each toleranced face of `result` (FaceInspection::tolerance) and sets result.verdict.
void judge_tolerances(const std::vector<FaceTolerance>& tolerances, InspectResult& result);

}  // namespace conform::detail
