#include "conform/pipelines/sicp_report.h"

namespace conform {

SicpReportFigures sicp_report_figures(const SicpJobResult& r, double min_confidence) {
  SicpReportFigures f;
  f.contour = r.contour.points;
  if (r.contour.closed && !f.contour.empty()) f.contour.push_back(f.contour.front());
  f.nominal = r.nominal.points;
  const SicpCompensationResult& c = r.compensation;
  f.compensated = c.trajectory.points;
  f.normals = spread_glyphs(c.trajectory.points, c.trajectory.normals, kSicpReportGlyphs);
  const std::vector<SicpRowReport>& rows = c.check.rows;
  f.row = row_numbers(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    f.across_mm.push_back(rows[i].across_mm);
    f.axis_mm.push_back(rows[i].axis_mm);
    f.along_mm.push_back(rows[i].along_mm);
    f.confidence.push_back(rows[i].confidence);
    if (rows[i].confidence < min_confidence && i < f.compensated.size()) f.untrusted.push_back(f.compensated[i]);
  }
  const SicpResult& g = c.registration;
  for (std::size_t k = 0; k < g.segments.size(); ++k) {
    f.segment.push_back(static_cast<double>(k));
    f.segment_rms_mm.push_back(g.segments[k].rms_mm);
    f.segment_confidence.push_back(k < c.check.segment_confidence.size() ? c.check.segment_confidence[k] : 0.0);
  }
  return f;
}

}  // namespace conform
