#pragma once
// The inputs of `conform align`, read and cleaned: what run_align composes.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cad.h"
#include "conform/core/mesh.h"
#include "conform/registration/point_pairs.h"

namespace conform::detail {

// A file's geometry in mm with non-finite points dropped (a warning says how many); throws conform::Error naming
// the file when it holds no points. A CAD file is tessellated with `cad` (its report appended to cad_reports) and
// keeps its own units.
Mesh read_for_alignment(const std::string& path, const char* what, double mm_per_unit,
                        std::vector<std::string>& warnings, const CadReadOptions& cad = {},
                        std::vector<CadReport>* cad_reports = nullptr);

// The points with exact duplicates merged, in first-seen order; `merged` counts the points removed.
std::vector<Eigen::Vector3d> unique_points(const std::vector<Eigen::Vector3d>& points, std::size_t* merged);

// Throws conform::Error suggesting --units when the two boxes' diagonals differ by more than max_ratio (> 0).
void check_sizes(const Mesh& scan, const Mesh& reference, const std::string& scan_path,
                 const std::string& reference_path, double max_ratio);

// The pairs file (align.h), the scan's coordinates times scan_mm_per_unit, the reference's times
// reference_mm_per_unit. Throws conform::Error naming the file and the line.
std::vector<PointPair> read_point_pairs(const std::string& path, double scan_mm_per_unit, double reference_mm_per_unit);

}  // namespace conform::detail
