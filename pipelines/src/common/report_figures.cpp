#include "conform/pipelines/common/report_figures.h"

#include "conform/core/error.h"

namespace conform {

std::vector<std::size_t> spread_indices(std::size_t n, std::size_t limit) {
  std::vector<std::size_t> out;
  if (limit == 0 || n == 0) return out;
  const std::size_t step = (n + limit - 1) / limit;
  for (std::size_t i = 0; i < n; i += step) out.push_back(i);
  if (out.back() != n - 1) out.push_back(n - 1);
  return out;
}

ReportGlyphs spread_glyphs(const std::vector<Eigen::Vector3d>& origins, const std::vector<Eigen::Vector3d>& directions,
                           std::size_t limit) {
  if (origins.size() != directions.size()) throw Error("report glyphs: one direction per origin");
  ReportGlyphs g;
  for (const std::size_t i : spread_indices(origins.size(), limit)) {
    g.origins.push_back(origins[i]);
    g.directions.push_back(directions[i]);
  }
  return g;
}

std::vector<double> row_numbers(std::size_t n) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = static_cast<double>(i + 1);
  return x;
}

}  // namespace conform
