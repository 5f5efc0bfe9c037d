#include "conform/compensation/profile_features.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

// The flat identity (Tx, Ty) -> (Ty, Tx, 0) and a strongly bent map: the profile wrapped on a cylinder of radius
// 2,000 mm about the z axis at (0, 2000) (Tx across, towards the centre), so that straight lines along Ty become arcs.
Eigen::Vector3d flat(const Eigen::Vector2d& q) { return {q.y(), q.x(), 0.0}; }
Eigen::Vector3d bent(const Eigen::Vector2d& q) {
  const double R = 2000.0, phi = q.y() / R;
  return {(R - q.x()) * std::sin(phi), R - (R - q.x()) * std::cos(phi), 0.0};
}

// The largest distance of the mapped outline's chord middles from the mapped outline (checked at 8 points a chord).
double worst_chord_error(const std::vector<Eigen::Vector2d>& designed, const ProfilePointMap& map) {
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < designed.size(); ++k) {
    const Eigen::Vector3d a = map(designed[k]), b = map(designed[k + 1]);
    for (int j = 1; j < 8; ++j) {
      const double f = j / 8.0;
      // A straight piece or an arc of the design: its middle points lie on the design segment or arc; the test's
      // features are lines and circles around (100, 500) of radius 50.
      Eigen::Vector2d q = designed[k] + f * (designed[k + 1] - designed[k]);
      const Eigen::Vector2d c(100.0, 500.0);
      if (std::abs((designed[k] - c).norm() - 50.0) < 1e-9 && std::abs((designed[k + 1] - c).norm() - 50.0) < 1e-9) {
        q = c + 50.0 * (q - c).normalized();
      }
      worst = std::max(worst, (map(q) - (a + f * (b - a))).norm());
    }
  }
  return worst;
}

TEST(ProfileFeatures, ParsesTypes) {
  ProfileFeatureType t = ProfileFeatureType::kPoint;
  for (const char* name : {"point", "circle", "slot", "polyline", "polygon"}) {
    EXPECT_TRUE(parse_profile_feature_type(name, &t));
    EXPECT_STREQ(to_string(t), name);
  }
  EXPECT_FALSE(parse_profile_feature_type("ellipse", &t));
}

TEST(ProfileFeatures, CircleMeetsTheChordToleranceAndCloses) {
  ProfileFeature circle{"H1", ProfileFeatureType::kCircle, {{100.0, 500.0}}, 50.0, ""};
  for (double tolerance : {0.5, 0.05, 0.005}) {
    ProfileSampleOptions options;
    options.chord_tolerance_mm = tolerance;
    for (const ProfilePointMap& map : {ProfilePointMap(flat), ProfilePointMap(bent)}) {
      const std::vector<Eigen::Vector2d> s = sample_profile_feature(circle, map, options);
      EXPECT_EQ(s.front(), s.back());  // closed
      // 1.1: the bisection tests chord middles, a chord's worst point may lie a little off its middle.
      EXPECT_LT(worst_chord_error(s, map), 1.1 * tolerance) << tolerance;
      // Not wastefully dense: within 2x of the flat count 2 pi / (2 acos(1 - tol / r)).
      const double needed = 2.0 * M_PI / (2.0 * std::acos(1.0 - tolerance / 50.0));
      EXPECT_LT(static_cast<double>(s.size()), 2.0 * needed + 8.0);
    }
  }
  Eigen::Vector2d c;
  EXPECT_TRUE(circle.centre(&c));
  EXPECT_EQ(c, Eigen::Vector2d(100.0, 500.0));
}

TEST(ProfileFeatures, LongLinesAreSplitWhereTheMapBends) {
  ProfileFeature line{"M1", ProfileFeatureType::kPolyline, {{185.0, 0.0}, {185.0, 2000.0}}, 0.0, ""};
  ProfileSampleOptions options;
  options.chord_tolerance_mm = 0.05;
  EXPECT_EQ(sample_profile_feature(line, ProfilePointMap(flat), options).size(), 2u);  // straight stays 2 points
  const std::vector<Eigen::Vector2d> s = sample_profile_feature(line, ProfilePointMap(bent), options);
  EXPECT_GT(s.size(), 10u);
  EXPECT_LT(worst_chord_error(s, ProfilePointMap(bent)), 0.05);
  EXPECT_EQ(s.front(), line.vertices.front());  // open: ends on its last vertex
  EXPECT_EQ(s.back(), line.vertices.back());
}

TEST(ProfileFeatures, SlotAndPolygonOutlines) {
  ProfileSampleOptions options;
  ProfileFeature slot{"S1", ProfileFeatureType::kSlot, {{100.0, 300.0}, {100.0, 400.0}}, 20.0, ""};
  const std::vector<Eigen::Vector2d> s = sample_profile_feature(slot, ProfilePointMap(flat), options);
  EXPECT_EQ(s.front(), s.back());
  double lo = 0.0, hi = 0.0;
  slot.ty_range(&lo, &hi);
  EXPECT_DOUBLE_EQ(lo, 280.0);
  EXPECT_DOUBLE_EQ(hi, 420.0);
  for (const Eigen::Vector2d& q : s) {
    // Every outline point lies at distance r from the centre line's segment (a stadium).
    const double f = std::clamp((q.y() - 300.0) / 100.0, 0.0, 1.0);
    EXPECT_NEAR((q - Eigen::Vector2d(100.0, 300.0 + 100.0 * f)).norm(), 20.0, 1e-9);
  }
  Eigen::Vector2d c;
  EXPECT_TRUE(slot.centre(&c));
  EXPECT_EQ(c, Eigen::Vector2d(100.0, 350.0));
  ProfileFeature polygon{"P1", ProfileFeatureType::kPolygon, {{0.0, 0.0}, {50.0, 0.0}, {50.0, 80.0}}, 0.0, ""};
  const std::vector<Eigen::Vector2d> p = sample_profile_feature(polygon, ProfilePointMap(flat), options);
  ASSERT_EQ(p.size(), 4u);  // the three vertices and back to the first
  EXPECT_EQ(p.front(), p.back());
}

TEST(ProfileFeatures, ValidationNamesTheFeature) {
  ProfileFeature circle{"H9", ProfileFeatureType::kCircle, {{100.0, 500.0}}, 0.0, "f.csv:7"};
  try {
    circle.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("f.csv:7: feature 'H9' (circle) needs a positive radius_mm"),
              std::string::npos)
        << e.what();
  }
  ProfileFeature line{"M", ProfileFeatureType::kPolyline, {{0.0, 0.0}}, 0.0, ""};
  EXPECT_THROW(line.validate(), Error);
  ProfileFeature slot{"S", ProfileFeatureType::kSlot, {{1.0, 1.0}, {1.0, 1.0}}, 5.0, ""};
  EXPECT_THROW(slot.validate(), Error);
  ProfileFeature point{"p", ProfileFeatureType::kPoint, {{1.0, 2.0}, {3.0, 4.0}}, 0.0, ""};
  EXPECT_THROW(point.validate(), Error);
}

TEST(ProfileFeatures, AbsurdValuesAreRefused) {
  // A broken export (9e18, 1e300) is not a design: refused by name, never mapped.
  for (double bad : {9e18, 1e300, -2e6}) {
    ProfileFeature f{"H1", ProfileFeatureType::kCircle, {{bad, 100.0}}, 5.0, "f.csv:2"};
    try {
      f.validate();
      FAIL() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("f.csv:2: feature 'H1' (circle) has the coordinate"), std::string::npos)
          << e.what();
    }
  }
  ProfileFeature huge{"H2", ProfileFeatureType::kCircle, {{100.0, 100.0}}, 1e300, ""};
  EXPECT_THROW(huge.validate(), Error);
  ProfileFeature fine{"H3", ProfileFeatureType::kCircle, {{100.0, 1e6}}, 50.0, ""};
  EXPECT_NO_THROW(fine.validate());
}

TEST(ProfileFeatures, TxRangeIncludesTheOutline) {
  ProfileFeature slot{"S", ProfileFeatureType::kSlot, {{100.0, 500.0}, {180.0, 600.0}}, 20.0, ""};
  double lo = 0.0, hi = 0.0;
  slot.tx_range(&lo, &hi);
  EXPECT_EQ(lo, 80.0);
  EXPECT_EQ(hi, 200.0);
}

}  // namespace
}  // namespace conform
