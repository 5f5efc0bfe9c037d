#pragma once
// What the job reports (pipelines/<job>_report.h) draw, before it is drawn: tool directions as glyphs, and the
// deterministic thinning that keeps a page's glyphs and lines readable (issue 21: big inputs decimated with a stated
// limit). Plain data, no page: each job's figures are tested against its Result before they reach report/.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace conform {

// Tool directions: where each glyph starts and its unit direction (the same count).
struct ReportGlyphs {
  std::vector<Eigen::Vector3d> origins;
  std::vector<Eigen::Vector3d> directions;
};

// About `limit` indices of [0, n) in order: every ceil(n / limit)-th from 0, and n - 1 (so that a decimated line
// still ends where it ended); limit 0: none. The same n, the same indices.
std::vector<std::size_t> spread_indices(std::size_t n, std::size_t limit);

// The glyphs at spread_indices(origins.size(), limit). origins and directions have the same size.
ReportGlyphs spread_glyphs(const std::vector<Eigen::Vector3d>& origins, const std::vector<Eigen::Vector3d>& directions,
                           std::size_t limit);

// 1, 2, ..., n as doubles: the x axis of a per-row plot (rows are numbered from 1, as the CLI prints them).
std::vector<double> row_numbers(std::size_t n);

}  // namespace conform
