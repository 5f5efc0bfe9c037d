#pragma once
// `conform inspect --tolerances FILE.csv`: per face the limits of its deviation and of its form, and per hole or boss
// (named by any of its faces) the limits of its size and position, and the verdicts.
//
//   face,lower_mm,upper_mm,form_mm,diameter_lower_mm,diameter_upper_mm,position_mm   (an empty cell or a missing
//   3,-0.05,0.05,0.03,,,                                                              column: not toleranced)
//   7,,,,11.95,12.05,0.1
//
// A face passes its profile limits when every assigned point's deviation lies in [lower, upper] (ISO 1101's surface
// profile: the whole surface within the zone), and its form when form_mm (InspectOptions::form_trim) is at most the
// given width. A feature passes its size when its least-squares diameter lies in [diameter_lower, diameter_upper],
// and its position when position_mm (the diameter of the zone about the nominal axis that holds the fitted axis,
// ISO 1101 position with a diameter zone) is at most the given one.

#include <string>
#include <vector>

#include "conform/core/cad_faces.h"
#include "conform/pipelines/inspect/inspect.h"

namespace conform::detail {

struct Tolerances {
  std::vector<FaceTolerance> faces;        // rows with a deviation or form limit
  std::vector<FeatureTolerance> features;  // rows with a size or position limit
};

// Reads the file (a `face` column and at least one limit column). Throws conform::Error naming the file and line: a
// face id not in 1..faces.size() or given twice, a number that is not one, lower > upper, a form or position width
// <= 0, a size or position limit on a face that is not a cylinder, two rows limiting one feature's size or position,
// a row that tolerances nothing.
Tolerances read_tolerances(const std::string& path, const std::vector<CadFace>& faces);

// Judges each toleranced face and feature of `result` and sets result.verdict: "fail" when one fails, else
// "incomplete" when one could not be measured, else "pass".
void judge_tolerances(const Tolerances& tolerances, InspectResult& result);

}  // namespace conform::detail
