#include "conform/pipelines/common/deviation_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "conform/pipelines/common/deviation_colours.h"
#include "common/deviation_axis.h"

namespace conform::html {
namespace {

constexpr std::size_t kBins = 60;
constexpr std::size_t kWorst = 5;  // callouts

// The points of largest |deviation|, at most kWorst, each at least 10 % of the points' extent from those before it
// (so that one bump does not take every callout), largest first.
std::vector<std::size_t> worst_points(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& d) {
  std::vector<std::size_t> order;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!std::isfinite(d[i]) || !points[i].allFinite()) continue;
    order.push_back(i);
    lo = lo.cwiseMin(points[i]), hi = hi.cwiseMax(points[i]);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&d](std::size_t a, std::size_t b) { return std::abs(d[a]) > std::abs(d[b]); });
  const double apart = order.empty() ? 0.0 : 0.1 * (hi - lo).norm();
  std::vector<std::size_t> out;
  for (std::size_t i : order) {
    if (out.size() == kWorst) break;
    bool far = true;
    for (std::size_t j : out) far = far && (points[i] - points[j]).norm() >= apart;
    if (far) out.push_back(i);
  }
  return out;
}

Table worst_table(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& d,
                  const std::vector<std::size_t>& worst, const DeviationView& v) {
  Table t{"Largest " + v.quantity + "s (the callouts in the view)",
          {"callout", "x (mm)", "y (mm)", "z (mm)", v.quantity + " (mm)"},
          {}};
  for (std::size_t k = 0; k < worst.size(); ++k) {
    const Eigen::Vector3d& p = points[worst[k]];
    t.rows.push_back({count(k + 1), number(p.x(), 3), number(p.y(), 3), number(p.z(), 3),
                      number(d[worst[k]], 4)});
  }
  return t;
}

std::string pointer(const DeviationView& v, const char* key) {
  return v.tie_to_json ? v.json_prefix + "/" + key : std::string();
}

Table statistics_table(const DeviationStatistics& s, const DeviationView& v) {
  Table t{"Statistics", {"figure", "value"}, {}};
  t.rows.push_back({"points measured", count(s.count, pointer(v, "matched"))});
  t.rows.push_back({"unmatched (grey)", count(s.excluded)});
  const std::pair<const char*, double> mm[] = {{"mean_mm", s.mean_mm}, {"std_mm", s.std_mm}, {"rms_mm", s.rms_mm},
                                               {"min_mm", s.min_mm},   {"max_mm", s.max_mm}, {"p5_mm", s.p5_mm},
                                               {"p50_mm", s.p50_mm},   {"p95_mm", s.p95_mm}, {"p99_mm", s.p99_mm},
                                               {"p95_abs_mm", s.p95_abs_mm}};
  for (const auto& [key, value] : mm) {
    std::string label(key);
    label = label.substr(0, label.size() - 3) + " (mm)";
    t.rows.push_back({label, number(value, 4, pointer(v, key))});
  }
  if (s.tolerance_mm) {
    t.rows.push_back({"tolerance +-t (mm)", number_g(*s.tolerance_mm, 6, pointer(v, "tolerance_mm"))});
    t.rows.push_back({"inside (%)", number(s.in_tolerance_pct, 2, pointer(v, "in_tolerance_pct"))});
    t.rows.push_back({"above (%)", number(s.above_pct, 2, pointer(v, "above_tolerance_pct"))});
    t.rows.push_back({"below (%)", number(s.below_pct, 2, pointer(v, "below_tolerance_pct"))});
  }
  return t;
}

}  // namespace

void add_deviation_view(Page& page, const std::vector<Eigen::Vector3d>& points, const std::vector<double>& deviation_mm,
                        const DeviationStatistics& s, const Mesh& reference, const DeviationView& view) {
  if (points.size() != deviation_mm.size()) {
    throw std::invalid_argument("add_deviation_view: " + std::to_string(deviation_mm.size()) + " deviations for " +
                                std::to_string(points.size()) + " points");
  }
  std::vector<Rgb> colours;
  colours.reserve(points.size());
  for (double d : deviation_mm) colours.push_back(deviation_colour(d, s));
  // Sparse scans get bigger dots, so that their colours read at a glance.
  const double size_px = points.size() < 20000 ? 4.0 : points.size() < 100000 ? 3.0 : 2.0;
  SceneObject& scan = page.scene.add_points(view.scan_name, points, colours, size_px);
  scan.values = deviation_mm;
  scan.value_label = view.quantity + " (mm)";
  const std::vector<std::size_t> worst = worst_points(points, deviation_mm);
  for (std::size_t k = 0; k < worst.size(); ++k) {
    char label[64];
    std::snprintf(label, sizeof label, "%zu: %+.3f mm", k + 1, deviation_mm[worst[k]]);
    page.scene.add_callout(points[worst[k]], label);
  }
  if (reference.has_faces()) {
    page.scene.add_mesh(view.reference_name, reference, {170, 176, 188}, view.reference_opacity);
  } else {
    page.scene.add_points(view.reference_name, reference.vertices, kGrey, 1.0).visible = false;
  }
  const double range = colour_scale_range_mm(s);
  ColourBar bar = make_colour_bar(view.quantity + " (mm)", "the PLY map's colours", -range, range,
                                  [&s](double d) { return deviation_colour(d, s); }, 129);
  if (s.tolerance_mm) bar.band = std::make_pair(-*s.tolerance_mm, *s.tolerance_mm);
  page.scene.set_colour_bar(std::move(bar));

  Section section;
  section.title = view.title;
  section.tables.push_back(statistics_table(s, view));
  if (!worst.empty()) section.tables.push_back(worst_table(points, deviation_mm, worst, view));
  std::vector<double> sorted;
  for (double d : deviation_mm) {
    if (std::isfinite(d)) sorted.push_back(d);
  }
  std::sort(sorted.begin(), sorted.end());
  if (!sorted.empty()) {
    const auto [lo, hi] = conform::detail::deviation_axis(sorted, s);
    Plot plot = histogram_plot(sorted, kBins, lo, hi, "Histogram of the " + view.quantity + "s",
                               view.quantity + " from the " + view.reference_name + " (mm)",
                               [&s](double d) { return deviation_colour(d, s); });
    plot.y_label = "points";
    plot.x_marks = {0.0};
    if (s.tolerance_mm) {
      char label[64];
      std::snprintf(label, sizeof label, "tolerance +-%g mm", *s.tolerance_mm);
      plot.x_band = Band{-*s.tolerance_mm, *s.tolerance_mm, label};
    }
    section.plots.push_back(std::move(plot));
  } else {
    section.paragraphs.push_back("No scan point was matched to the reference: no deviations to show.");
  }
  page.sections.push_back(std::move(section));
}

}  // namespace conform::html
