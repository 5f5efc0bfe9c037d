// The seam's closed form against independent checks: the paper's own equations, both cylinder equations evaluated
// through the joint frames, finite differences of the curve, and normals from finite-difference gradients.

#include "conform/toolpath/saddle/saddle_curve.h"
#include "saddle_test_geometry.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/toolpath/intersection/joint_frames.h"

namespace conform {
namespace {

SaddleGeometry geometry(double R, double r, double pitch_deg, double offset) {
  return test::saddle_geometry(R, r, pitch_deg, offset);
}

// Joints from the paper's to steep, offset and nearly-tangent ones.
std::vector<SaddleGeometry> joints() {
  return {geometry(600, 150, 90, 0),    geometry(600, 150, 45, 100), geometry(600, 150, 30, -200),
          geometry(1000, 500, 60, 250), geometry(300, 280, 75, 0),   geometry(600, 150, 10, 50)};
}

std::vector<double> azimuths(int n) {
  std::vector<double> out;
  for (int i = 0; i <= n; ++i) out.push_back(2 * kPi * i / n + 1e-3 * std::sin(i));
  return out;
}

TEST(SaddleCurve, RightAngleJointIsThePapersCurve) {
  const double R = 600, r = 150, phi0 = kPi / 4;
  const SaddleCurve curve(geometry(R, r, 90, 0));
  for (double theta : azimuths(1000)) {
    // Eq. 1-3 and 7.
    const double x = r * std::sin(theta), y = r * std::cos(theta);
    const double z = std::sqrt(R * R - r * r * std::sin(theta) * std::sin(theta));
    const Eigen::Vector3d p = curve.point(theta);
    EXPECT_NEAR(p.x(), x, 1e-12);
    EXPECT_NEAR(p.y(), y, 1e-12);
    EXPECT_NEAR(p.z(), z, 1e-12);
    // Eq. 10-12.
    const double beta = std::acos(x * x / (R * r));
    EXPECT_NEAR(curve.dihedral(theta), beta, 1e-12) << theta;
    EXPECT_NEAR(curve.pose(theta, phi0), kPi / 2 - beta + phi0, 1e-12) << theta;
  }
}

TEST(SaddleCurve, PointsLieOnBothCylindersWithinAPicometre) {
  for (const SaddleGeometry& g : joints()) {
    const SaddleCurve curve(g);
    const Eigen::Isometry3d T = T_L_P(g.joint());  // independent of the curve's own residual code
    for (double phi : azimuths(2000)) {
      const Eigen::Vector3d p = curve.point(phi);
      const Eigen::Vector3d p_L = T * p;
      EXPECT_LE(std::abs(std::hypot(p.x(), p.y()) - g.pipe_radius_mm), 1e-9);
      EXPECT_LE(std::abs(std::hypot(p_L.x(), p_L.y()) - g.leg_radius_mm), 1e-9) << g.pitch_rad << " " << phi;
      EXPECT_GT(p_L.x(), 0.0);  // on the side of the leg the stub comes from
      EXPECT_LE(curve.pipe_residual(p), 1e-9);
      EXPECT_LE(curve.leg_residual(p), 1e-9);
    }
  }
}

TEST(SaddleCurve, DerivativeMatchesCentralDifferences) {
  const double h = 1e-5;
  for (const SaddleGeometry& g : joints()) {
    const SaddleCurve curve(g);
    for (double phi : azimuths(500)) {
      const Eigen::Vector3d fd = (curve.point(phi + h) - curve.point(phi - h)) / (2 * h);
      const Eigen::Vector3d d = curve.derivative(phi);
      EXPECT_LE((fd - d).norm(), 1e-6 * d.norm()) << g.pitch_rad << " " << phi;
    }
  }
}

// Outward unit normal of an implicit surface F = 0 (F < 0 inside) by central differences of F.
Eigen::Vector3d gradient_normal(const std::function<double(const Eigen::Vector3d&)>& F, const Eigen::Vector3d& p) {
  const double h = 1e-4;
  Eigen::Vector3d g;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * h;
    g[k] = (F(p + e) - F(p - e)) / (2 * h);
  }
  return g.normalized();
}

TEST(SaddleCurve, DihedralAngleIsTheAngleBetweenTheSurfaceNormals) {
  for (const SaddleGeometry& g : joints()) {
    const SaddleCurve curve(g);
    const Eigen::Isometry3d T = T_L_P(g.joint());
    const auto pipe = [&](const Eigen::Vector3d& p) {
      return p.x() * p.x() + p.y() * p.y() - g.pipe_radius_mm * g.pipe_radius_mm;
    };
    const auto leg = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector3d q = T * p;
      return q.x() * q.x() + q.y() * q.y() - g.leg_radius_mm * g.leg_radius_mm;
    };
    for (double phi : azimuths(300)) {
      const Eigen::Vector3d p = curve.point(phi);
      const Eigen::Vector3d n_pipe = gradient_normal(pipe, p);
      const Eigen::Vector3d n_leg = gradient_normal(leg, p);
      EXPECT_LE((n_pipe - curve.pipe_normal(phi)).norm(), 1e-8);
      EXPECT_LE((n_leg - curve.leg_normal(phi)).norm(), 1e-8);
      EXPECT_NEAR(curve.dihedral(phi), std::acos(n_pipe.dot(n_leg)), 1e-7) << phi;
      // The seam's tangent lies in both tangent planes.
      const Eigen::Vector3d t = curve.derivative(phi).normalized();
      EXPECT_NEAR(t.dot(n_pipe), 0.0, 1e-8);
      EXPECT_NEAR(t.dot(n_leg), 0.0, 1e-8);
    }
  }
}

TEST(SaddleCurve, SinAlphaIsTheSeamsSlopeAgainstThePipeAxis) {
  for (const SaddleGeometry& g : joints()) {
    const SaddleCurve curve(g);
    for (double phi : azimuths(300)) {
      // The seam advances r dphi around the pipe for every |dP/dphi| dphi along itself.
      EXPECT_NEAR(curve.sin_alpha(phi), g.pipe_radius_mm / curve.derivative(phi).norm(), 1e-12) << phi;
    }
  }
}

TEST(SaddleCurve, ArcLengthMatchesAFineChordSum) {
  for (const SaddleGeometry& g : joints()) {
    const SaddleCurve curve(g);
    // Chord sums under-estimate by ~ L (kappa h)^2 / 24: Richardson extrapolation of two of them.
    const auto chords = [&](int n) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += (curve.point(2 * kPi * (i + 1) / n) - curve.point(2 * kPi * i / n)).norm();
      return sum;
    };
    const double extrapolated = (4 * chords(40000) - chords(20000)) / 3;
    const double length = curve.arc_length(0.0, 2 * kPi);
    EXPECT_NEAR(length, extrapolated, 1e-8 * length) << g.pitch_rad;
    EXPECT_NEAR(curve.arc_length(0.0, 1.0) + curve.arc_length(1.0, 2 * kPi), length, 1e-9 * length);
    EXPECT_GT(length, 2 * kPi * g.pipe_radius_mm);  // longer than the pipe's circumference
  }
}

void expect_invalid(const SaddleGeometry& g, const std::string& words) {
  std::string error;
  EXPECT_FALSE(g.IsValid(&error));
  EXPECT_NE(error.find(words), std::string::npos) << error;
  try {
    SaddleCurve curve(g);
    ADD_FAILURE() << "accepted: " << words;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(SaddleCurve, RejectsJointsWithoutOneClosedSeam) {
  expect_invalid(geometry(150, 150.001, 90, 0), "must not be larger than the cylinder radius");
  expect_invalid(geometry(100, 150, 90, 0), "must not be larger than the cylinder radius");
  expect_invalid(geometry(0, 150, 90, 0), "must be positive");
  expect_invalid(geometry(600, -1, 90, 0), "must be positive");
  expect_invalid(geometry(600, 150, 0, 0), "outside [1, 90] deg");
  expect_invalid(geometry(600, 150, 0.99, 0), "outside [1, 90] deg");
  expect_invalid(geometry(600, 150, 1e-300, 0), "outside [1, 90] deg");
  expect_invalid(geometry(600, 150, 91, 0), "outside [1, 90] deg");
  expect_invalid(geometry(600, 150, -30, 0), "outside [1, 90] deg");
  expect_invalid(geometry(600, 150, 90, 450.001), "offset 450.001 mm is too large");
  expect_invalid(geometry(600, 150, 90, -500), "too large");
  expect_invalid(geometry(std::nan(""), 150, 90, 0), "finite");
  expect_invalid(geometry(1e300, 150, 90, 0), "beyond");  // a CSV of inf and nan before
  expect_invalid(geometry(1.000001e6, 150, 90, 0), "beyond");
  EXPECT_TRUE(geometry(1e6, 150, 90, 0).IsValid(nullptr));
  EXPECT_TRUE(geometry(600, 150, 90, 449).IsValid(nullptr));
  EXPECT_TRUE(geometry(600, 150, 90, 450).IsValid(nullptr));  // touches the cylinder: one corner
  EXPECT_TRUE(geometry(150, 150, 1, 0).IsValid(nullptr));     // equal diameters, the lowest pitch
}

}  // namespace
}  // namespace conform
