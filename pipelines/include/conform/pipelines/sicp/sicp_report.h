#pragma once
// The report of `conform sicp --report FILE.html` (issue 21): the scan, the nominal contour, the nominal and the
// compensated trajectories with their tool normals in 3D; per-row correction (across the edge, along the tool axis,
// along the path) and confidence, per-segment residual and confidence as plots; the figures the CLI prints as tables.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/pipelines/common/report_figures.h"
#include "conform/pipelines/sicp/sicp.h"
#include "conform/report/page.h"

namespace conform {

// Tool-normal glyphs drawn at most (every k-th row).
constexpr std::size_t kSicpReportGlyphs = 400;

struct SicpReportFigures {
  std::vector<Eigen::Vector3d> contour;      // the nominal contour; a closed one ends on its first point
  std::vector<Eigen::Vector3d> nominal;      // nominal trajectory rows
  std::vector<Eigen::Vector3d> compensated;  // compensated rows (the Result's trajectory)
  ReportGlyphs normals;                      // compensated tool normals, at most kSicpReportGlyphs
  std::vector<Eigen::Vector3d> untrusted;    // compensated rows below the checks' min_confidence
  // Per row (x: row number from 1), the correction in the compensated row's frame and the row's confidence.
  std::vector<double> row, across_mm, axis_mm, along_mm, confidence;
  // Per segment (x: segment index from 0, as the JSON's "index"), S-ICP only.
  std::vector<double> segment, segment_rms_mm, segment_confidence;
};

// The figures of a run with keep_geometry (the contour and the nominal trajectory are empty without it).
// min_confidence: the checks' threshold (SicpCheckOptions::min_confidence).
SicpReportFigures sicp_report_figures(const SicpJobResult& result, double min_confidence);

// The page: header (inputs, options, verdict: trusted, or why not), the 3D view (a run with keep_geometry), tables of
// the figures `conform sicp` prints (cells tied to sicp_json), the per-row and per-segment plots. Page::date is left
// to the caller.
html::Page sicp_report(const SicpJobOptions& options, const SicpJobResult& result);

}  // namespace conform
