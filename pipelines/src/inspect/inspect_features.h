#pragma once
// The figures of one CAD face from the scan points assigned to it (pipelines/inspect/inspect.h): deviation statistics,
// the fitted feature (least-squares plane, fitting/cylinder.h's cylinder) against its nominal, and the form zone.

#include <vector>

#include <Eigen/Core>

#include "conform/pipelines/inspect/inspect.h"

namespace conform::detail {

// `points` in the part frame, mm; `normals` their scan normals (unit, sign ignored); `deviation_mm` their signed
// deviation from the nominal face (+ outside). Fills every measured field of `face` (its id and nominal are set).
void measure_face(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                  const std::vector<double>& deviation_mm, const InspectOptions& options, FaceInspection& face);

}  // namespace conform::detail
