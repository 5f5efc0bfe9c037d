// Interpolation of the saddle seam: the paper's Table 1, constant torch speed, and the generalised joint.

#include "conform/toolpath/saddle/saddle.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/toolpath/intersection/joint_frames.h"

namespace conform {
namespace {

// Xue et al. (2018), Table 1 "The interpolation data" (R = 600 mm, r = 150 mm, phi0 = pi/4, steps of pi/20), as
// printed: rotation angle theta (rad), x, y, z (mm), torch pose angle (rad). Source: the article's web edition,
// https://www.hindawi.com/journals/mse/2018/8045162/tab1 (doi 10.1155/2018/8045162).
constexpr std::array<std::array<double, 5>, 41> kTable1 = {{
    {0.0000, 0.0000, 150.0000, 600.0000, 0.7854},    {0.1571, 23.4652, 148.1533, 599.5410, 0.7915},
    {0.3142, 46.3525, 142.6585, 598.2069, 0.8093},   {0.4712, 68.0986, 133.6510, 596.1230, 0.8369},
    {0.6283, 88.1678, 121.3525, 593.4867, 0.8719},   {0.7854, 106.0660, 106.0660, 590.5506, 0.9107},
    {0.9425, 121.3525, 88.1678, 587.5998, 0.9498},   {1.0996, 133.6510, 68.0986, 584.9251, 0.9852},
    {1.2566, 142.6585, 46.3525, 582.7938, 1.0135},   {1.4137, 148.1533, 23.4652, 581.4212, 1.0318},
    {1.5708, 150.0000, 0.0000, 580.9475, 1.0381},    {1.7279, 148.1533, -23.4652, 581.4212, 1.0318},
    {1.8850, 142.6585, -46.3525, 582.7938, 1.0135},  {2.0420, 133.6510, -68.0986, 584.9251, 0.9852},
    {2.1991, 121.3525, -88.1678, 587.5998, 0.9498},  {2.3562, 106.0660, -106.0660, 590.5506, 0.9107},
    {2.5133, 88.1678, -121.3525, 593.4867, 0.8719},  {2.6704, 68.0986, -133.6510, 596.1230, 0.8369},
    {2.8274, 46.3525, -142.6585, 598.2069, 0.8093},  {2.9845, 23.4652, -148.1533, 599.5410, 0.7915},
    {3.1416, 0.0000, -150.0000, 600.0000, 0.7854},   {3.2987, -23.4652, -148.1533, 599.5410, 0.7915},
    {3.4558, -46.3525, -142.6585, 598.2069, 0.8093}, {3.6128, -68.0986, -133.6510, 596.1230, 0.8369},
    {3.7699, -88.1678, -121.3525, 593.4867, 0.8719}, {3.9270, -106.0660, -106.0660, 590.5506, 0.9107},
    {4.0841, -121.3525, -88.1678, 587.5998, 0.9498}, {4.2412, -133.6510, -68.0986, 584.9251, 0.9852},
    {4.3982, -142.6585, -46.3525, 582.7938, 1.0135}, {4.5553, -148.1533, -23.4652, 581.4212, 1.0318},
    {4.7124, -150.0000, 0.0000, 580.9475, 1.0381},   {4.8695, -148.1533, 23.4652, 581.4212, 1.0318},
    {5.0265, -142.6585, 46.3525, 582.7938, 1.0135},  {5.1836, -133.6510, 68.0986, 584.9251, 0.9852},
    {5.3407, -121.3525, 88.1678, 587.5998, 0.9498},  {5.4978, -106.0660, 106.0660, 590.5506, 0.9107},
    {5.6549, -88.1678, 121.3525, 593.4867, 0.8719},  {5.8119, -68.0986, 133.6510, 596.1230, 0.8369},
    {5.9690, -46.3525, 142.6585, 598.2069, 0.8093},  {6.1261, -23.4652, 148.1533, 599.5410, 0.7915},
    {6.2832, 0.0000, 150.0000, 600.0000, 0.7854},
}};

// Half a unit in the 4th printed decimal, plus rounding slack.
constexpr double kPrinted = 0.5e-4 + 1e-9;

SaddleOptions papers_options() {
  SaddleOptions options;  // defaults: R 600, r 150, pitch pi/2, offset 0, phi0 pi/4, equal steps of pi/20
  return options;
}

TEST(Saddle, ReproducesThePapersTable1ToItsPrintedDecimals) {
  const SaddleResult result = interpolate_saddle(papers_options());
  ASSERT_EQ(result.points.size(), kTable1.size());
  for (std::size_t i = 0; i < kTable1.size(); ++i) {
    const SaddlePoint& p = result.points[i];
    const auto& row = kTable1[i];
    EXPECT_NEAR(p.theta_rad, row[0], kPrinted) << "row " << i + 1;
    EXPECT_NEAR(p.position.x(), row[1], kPrinted) << "row " << i + 1;
    EXPECT_NEAR(p.position.y(), row[2], kPrinted) << "row " << i + 1;
    EXPECT_NEAR(p.position.z(), row[3], kPrinted) << "row " << i + 1;
    EXPECT_NEAR(p.pose_rad, row[4], kPrinted) << "row " << i + 1;
  }
  // Row 11 as the issue quotes it.
  const SaddlePoint& row11 = result.points[10];
  EXPECT_NEAR(row11.theta_rad, 1.5708, kPrinted);
  EXPECT_NEAR(row11.position.x(), 150.0000, kPrinted);
  EXPECT_NEAR(row11.position.y(), 0.0000, kPrinted);
  EXPECT_NEAR(row11.position.z(), 580.9475, kPrinted);
  EXPECT_NEAR(row11.pose_rad, 1.0381, kPrinted);
  EXPECT_EQ(result.points.back().theta_rad, 2 * kPi);
  EXPECT_FALSE(result.last_step_partial);
}

TEST(Saddle, Table1RowsFollowThePapersClosedForms) {
  const double R = 600, r = 150, phi0 = kPi / 4;
  const SaddleResult result = interpolate_saddle(papers_options());
  for (std::size_t i = 0; i < result.points.size(); ++i) {
    const double theta = static_cast<double>(i) * kPi / 20;  // equal angles of pi/20 (0.1571 rad)
    const SaddlePoint& p = result.points[i];
    const double x = r * std::sin(theta);                             // Eq. 1-3
    const double z = std::sqrt(R * R - x * x);                        // Eq. 7
    const double pose = kPi / 2 - std::acos(x * x / (R * r)) + phi0;  // Eq. 10-12
    EXPECT_NEAR(p.theta_rad, theta, 1e-12);
    EXPECT_NEAR(p.position.x(), x, 1e-9);
    EXPECT_NEAR(p.position.y(), r * std::cos(theta), 1e-9);
    EXPECT_NEAR(p.position.z(), z, 1e-9);
    EXPECT_NEAR(p.pose_rad, pose, 1e-9);
  }
}

TEST(Saddle, EqualAngleShortensTheLastStepToLandOnTwoPi) {
  SaddleOptions options = papers_options();
  options.step_rad = 7.0 / 180 * kPi;  // 360 / 7 = 51.4 steps
  const SaddleResult result = interpolate_saddle(options);
  ASSERT_EQ(result.points.size(), 53u);
  EXPECT_EQ(result.points.back().theta_rad, 2 * kPi);
  EXPECT_NEAR(result.points[51].theta_rad, 51 * options.step_rad, 1e-12);
  EXPECT_TRUE(result.last_step_partial);
  EXPECT_EQ(result.full_steps, 51u);
  EXPECT_LT(result.last_step_mm, 0.5 * result.step_mm_min);  // 0.43 of a step, left out of the ripple
  EXPECT_LE((result.points.back().position - result.points.front().position).norm(), 1e-9);  // closed
}

struct Ripples {
  SaddleResult constant_speed;
  SaddleResult equal_angle;
};

// Constant-speed interpolation with step v dT, and equal-angle interpolation with the same mean step (2 pi / N for the
// same number N of full steps).
Ripples measure(SaddleOptions options, SaddleStepRule rule, double speed_mm_per_s, double period_s) {
  options.rule = rule;
  options.speed_mm_per_s = speed_mm_per_s;
  options.period_s = period_s;
  Ripples out;
  out.constant_speed = interpolate_saddle(options);
  options.rule = SaddleStepRule::kEqualAngle;
  options.step_rad = 2 * kPi / std::round(out.constant_speed.curve_length_mm / (speed_mm_per_s * period_s));
  out.equal_angle = interpolate_saddle(options);
  std::printf(
      "[ measured ] %s v dT = %.6g mm: %zu points, steps %.9g..%.9g mm, ripple %.3g %% (max %d iterations);"
      " equal-angle at mean step %.9g mm: ripple %.4f %%\n",
      to_string(rule), speed_mm_per_s * period_s, out.constant_speed.points.size(), out.constant_speed.step_mm_min,
      out.constant_speed.step_mm_max, out.constant_speed.speed_ripple_pct, out.constant_speed.max_iterations,
      out.equal_angle.step_mm_mean, out.equal_angle.speed_ripple_pct);
  return out;
}

void expect_constant_speed(const Ripples& m, double step_mm) {
  const SaddleResult& s = m.constant_speed;
  EXPECT_TRUE(s.converged) << s.termination;
  EXPECT_LT(s.speed_ripple_pct, 0.1);
  EXPECT_NEAR(s.step_mm_mean, step_mm, 1e-4 * step_mm);
  EXPECT_NEAR(m.equal_angle.step_mm_mean, step_mm, 1e-3 * step_mm);
  EXPECT_GT(m.equal_angle.speed_ripple_pct, 100 * s.speed_ripple_pct);
  EXPECT_EQ(s.points.back().theta_rad, 2 * kPi);
  EXPECT_LE(s.last_step_mm, step_mm * (1 + 1e-9));
  for (std::size_t i = 1; i < s.points.size(); ++i) ASSERT_GT(s.points[i].theta_rad, s.points[i - 1].theta_rad);
}

TEST(Saddle, VariableAngleKeepsThePapersWeldingSpeedConstant) {
  // v = 80 mm/min, dT = 4 ms: v dT = 5.33 um per period, ~177,000 points.
  const Ripples m = measure(papers_options(), SaddleStepRule::kVariableAngle, 80.0 / 60.0, 0.004);
  expect_constant_speed(m, 80.0 / 60.0 * 0.004);
  EXPECT_GT(m.equal_angle.speed_ripple_pct, 0.5);
}

TEST(Saddle, VariableAngleKeepsTwoMillimetreStepsConstant) {
  const Ripples m = measure(papers_options(), SaddleStepRule::kVariableAngle, 500.0, 0.004);  // v dT = 2 mm
  expect_constant_speed(m, 2.0);
  EXPECT_GT(m.equal_angle.speed_ripple_pct, 0.5);
}

TEST(Saddle, VariableAngleStepsAreTheArcLengthToThirdOrder) {
  SaddleOptions options = papers_options();
  options.rule = SaddleStepRule::kVariableAngle;
  options.speed_mm_per_s = 500.0;
  const SaddleResult result = interpolate_saddle(options);
  const SaddleCurve curve(options.geometry);
  for (std::size_t i = 1; i + 1 < result.points.size(); ++i) {
    const double arc = curve.arc_length(result.points[i - 1].theta_rad, result.points[i].theta_rad);
    EXPECT_NEAR(arc, 2.0, 1e-5) << i;  // the midpoint rule of Eq. 24: error ~ (dtheta)^3
  }
}

TEST(Saddle, VariableAngleSolvesEquation24WhereFixedPointIterationStalls) {
  // A pipe nearly as wide as the cylinder, steps as long as its radius: the fixed point is no contraction there, and
  // the bracketed fallback must still solve dtheta = v dT sin(alpha(theta + dtheta / 2)) / r.
  SaddleOptions options;
  options.geometry.leg_radius_mm = 100.0;
  options.geometry.pipe_radius_mm = 99.0;
  options.rule = SaddleStepRule::kVariableAngle;
  options.speed_mm_per_s = 99.0;
  options.period_s = 1.0;
  const SaddleResult result = interpolate_saddle(options);
  EXPECT_TRUE(result.converged) << result.termination;
  EXPECT_GT(result.max_iterations, 60);  // the fallback ran
  const SaddleCurve curve(options.geometry);
  for (std::size_t i = 1; i + 1 < result.points.size(); ++i) {
    const double theta = result.points[i - 1].theta_rad;
    const double step = result.points[i].theta_rad - theta;
    EXPECT_NEAR(step, 99.0 * curve.sin_alpha(theta + 0.5 * step) / 99.0, 1e-12) << i;
  }
}

SaddleOptions general_options(double pitch_deg, double offset_mm) {
  SaddleOptions options = papers_options();
  options.geometry.pitch_rad = pitch_deg / 180 * kPi;
  options.geometry.offset_mm = offset_mm;
  return options;
}

TEST(Saddle, ArcLengthStepsAreExactForAPitchedOffsetJoint) {
  const SaddleOptions options = general_options(45, 100);
  const Ripples m = measure(options, SaddleStepRule::kArcLength, 500.0, 0.004);
  expect_constant_speed(m, 2.0);
  const SaddleResult& s = m.constant_speed;
  const SaddleCurve curve(options.geometry);
  for (std::size_t i = 1; i + 1 < s.points.size(); ++i) {
    EXPECT_NEAR(curve.arc_length(s.points[i - 1].theta_rad, s.points[i].theta_rad), 2.0, 1e-10) << i;
  }
  EXPECT_LE(s.max_pipe_residual_mm, 1e-9);
  EXPECT_LE(s.max_leg_residual_mm, 1e-9);
  std::printf("[ measured ] pitch 45 deg, offset 100 mm: residual pipe %.3g mm, cylinder %.3g mm\n",
              s.max_pipe_residual_mm, s.max_leg_residual_mm);
}

TEST(Saddle, GeneralJointPointsLieOnBothCylinders) {
  for (double pitch : {30.0, 45.0, 60.0}) {
    for (double offset : {-200.0, 0.0, 100.0}) {
      SaddleOptions options = general_options(pitch, offset);
      options.step_rad = kPi / 720;
      const SaddleResult result = interpolate_saddle(options);
      const Eigen::Isometry3d T = T_L_P(options.geometry.joint());
      for (const SaddlePoint& p : result.points) {
        const Eigen::Vector3d q = T * p.position;
        ASSERT_LE(std::abs(std::hypot(p.position.x(), p.position.y()) - 150.0), 1e-9);
        ASSERT_LE(std::abs(std::hypot(q.x(), q.y()) - 600.0), 1e-9) << pitch << " " << offset;
      }
      EXPECT_LE(result.max_leg_residual_mm, 1e-9);
    }
  }
}

TEST(Saddle, RightAngleWithoutOffsetIsThePapersPathForEveryRule) {
  for (SaddleStepRule rule : {SaddleStepRule::kVariableAngle, SaddleStepRule::kArcLength}) {
    SaddleOptions options = general_options(90, 0);
    options.rule = rule;
    options.speed_mm_per_s = 250.0;
    const SaddleResult result = interpolate_saddle(options);
    for (const SaddlePoint& p : result.points) {
      const double x = 150 * std::sin(p.theta_rad);
      ASSERT_NEAR(p.position.z(), std::sqrt(600.0 * 600.0 - x * x), 1e-9);
      ASSERT_NEAR(p.pose_rad, kPi / 2 - std::acos(x * x / 90000.0) + kPi / 4, 1e-9);
    }
  }
}

TEST(Saddle, SameInputGivesTheSameNumbers) {
  SaddleOptions options = general_options(60, 30);
  options.rule = SaddleStepRule::kVariableAngle;
  options.speed_mm_per_s = 300.0;
  const SaddleResult a = interpolate_saddle(options);
  const SaddleResult b = interpolate_saddle(options);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i].position, b.points[i].position);
}

void expect_rejected(const SaddleOptions& options, const std::string& words) {
  std::string error;
  EXPECT_FALSE(options.IsValid(&error)) << words;
  EXPECT_NE(error.find(words), std::string::npos) << error;
  try {
    interpolate_saddle(options);
    ADD_FAILURE() << "accepted: " << words;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(Saddle, RejectsBadStepsSpeedsAndPeriods) {
  SaddleOptions options = papers_options();
  options.step_rad = 0.0;
  expect_rejected(options, "angle step 0 deg is outside (0, 180) deg");
  options.step_rad = 7.0;
  expect_rejected(options, "outside (0, 180) deg");
  options.step_rad = kPi;  // a half turn would skip the far side of the seam
  expect_rejected(options, "outside (0, 180) deg");
  options = papers_options();
  options.rule = SaddleStepRule::kVariableAngle;
  options.speed_mm_per_s = 0.0;
  expect_rejected(options, "speed 0 mm/s must be a positive number");
  options.speed_mm_per_s = 1.0;
  options.period_s = -0.004;
  expect_rejected(options, "period -0.004 s must be a positive number");
  options.rule = SaddleStepRule::kArcLength;
  options.period_s = 200.0;
  expect_rejected(options, "longer than the pipe radius");
  options = papers_options();
  options.start_pose_rad = std::nan("");
  expect_rejected(options, "must be a number in (-180, 180] deg");
  options.start_pose_rad = 1e308;
  expect_rejected(options, "must be a number in (-180, 180] deg");
  options.start_pose_rad = -kPi;
  expect_rejected(options, "must be a number in (-180, 180] deg");
  options.start_pose_rad = kPi;
  EXPECT_NO_THROW(interpolate_saddle(options));
  options = papers_options();
  options.geometry.pipe_radius_mm = 600.001;
  expect_rejected(options, "must not be larger than the cylinder radius");
  options = papers_options();
  options.step_rad = 1e-7;
  options.max_points = 1000;
  try {
    interpolate_saddle(options);
    ADD_FAILURE() << "a path of 6e7 points was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("step is too small"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace conform
