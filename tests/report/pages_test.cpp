// The pieces the jobs' pages are built from: the deviation view (every point in the deviation map's colour, the
// colour bar's band at +-t, the histogram holding every finite deviation, the statistics tied to compare's JSON keys)
// and the fitted cylinder's mesh (vertices on the surface, faces facing out).

#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "conform/pipelines/fit_cylinder/fit_cylinder_report.h"
#include "conform/pipelines/common/deviation_colours.h"
#include "conform/pipelines/common/deviation_view.h"

namespace conform {
namespace {

TEST(ReportPages, DeviationViewColoursBandHistogramAndTies) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> d;
  for (int i = 0; i < 200; ++i) {
    points.emplace_back(i, 0.5 * i, 0.0);
    d.push_back(i == 7 ? NAN : 0.01 * (i - 100));
  }
  DeviationStatisticsOptions o;
  o.tolerance_mm = 0.5;
  const DeviationStatistics s = deviation_statistics(d, o);
  Mesh reference;
  reference.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  reference.faces = {{0, 1, 2}};
  html::Page page;
  html::add_deviation_view(page, points, d, s, reference);
  ASSERT_EQ(page.scene.objects().size(), 2u);
  const html::SceneObject& scan = page.scene.objects()[0];
  ASSERT_EQ(scan.colours.size(), points.size());
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(scan.colours[i], deviation_colour(d[i], s)) << i;
  EXPECT_EQ(page.scene.objects()[1].kind, html::ObjectKind::kMesh);
  ASSERT_TRUE(page.scene.colour_bar().has_value());
  EXPECT_DOUBLE_EQ(page.scene.colour_bar()->band->first, -0.5);
  EXPECT_DOUBLE_EQ(page.scene.colour_bar()->band->second, 0.5);
  EXPECT_DOUBLE_EQ(page.scene.colour_bar()->max, colour_scale_range_mm(s));
  ASSERT_EQ(page.sections.size(), 1u);
  const html::Plot& plot = page.sections[0].plots.at(0);
  double total = 0.0;
  for (const html::Bar& b : plot.bars) total += b.count;
  EXPECT_DOUBLE_EQ(total, 199.0);  // every finite deviation, the NaN left out
  ASSERT_TRUE(plot.x_band.has_value());
  bool rms_tied = false;
  for (const auto& row : page.sections[0].tables.at(0).rows) {
    if (row[1].json_pointer == "/rms_mm") rms_tied = std::abs(std::stod(row[1].text) - s.rms_mm) < 5e-5;
  }
  EXPECT_TRUE(rms_tied);
  EXPECT_THROW(html::add_deviation_view(page, points, {0.0}, s, reference), std::invalid_argument);
}

TEST(ReportPages, CylinderMeshOnTheSurfaceFacingOut) {
  Cylinder c;
  c.axis_point = {10, -5, 3};
  c.axis_direction = Eigen::Vector3d(1, 2, 2).normalized();
  c.radius_mm = 42.0;
  const Mesh m = cylinder_mesh(c, -20.0, 35.0, 48, 5);
  EXPECT_EQ(m.vertices.size(), 48u * 6u);
  EXPECT_EQ(m.faces.size(), 2u * 48u * 5u);
  double t_min = 1e9, t_max = -1e9;
  for (const Eigen::Vector3d& v : m.vertices) {
    EXPECT_NEAR(std::abs(signed_distance(c, v)), 0.0, 1e-9);
    const double t = (v - c.axis_point).dot(c.axis_direction);
    t_min = std::min(t_min, t), t_max = std::max(t_max, t);
  }
  EXPECT_NEAR(t_min, -20.0, 1e-9);
  EXPECT_NEAR(t_max, 35.0, 1e-9);
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const Eigen::Vector3d centre =
        (m.vertices[m.faces[f][0]] + m.vertices[m.faces[f][1]] + m.vertices[m.faces[f][2]]) / 3.0;
    const Eigen::Vector3d w = centre - c.axis_point;
    const Eigen::Vector3d radial = w - w.dot(c.axis_direction) * c.axis_direction;
    EXPECT_GT(face_normal(m, f).dot(radial.normalized()), 0.9) << f;
  }
}

}  // namespace
}  // namespace conform
