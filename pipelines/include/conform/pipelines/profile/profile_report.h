#pragma once
// The report of `conform profile --report FILE.html` (issue 21): the measured edge and its fitted curve, and every
// designed feature twice in 3D: where it would lie on the straight profile (nominal) and where it is cut on the
// deformed one (mapped); per-feature displacement as a table and along the profile as a plot.
//
// The straight profile (nominal): origin C(s = 0), along the chord from C(0) to C(L), across Z x along with Z the
// global web normal of the run (machine +z for a local web): the profile as designed, laid along the measured edge's
// ends. A feature's displacement is |mapped - nominal| point by point: how far the deformation moves it.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/pipelines/profile/profile.h"
#include "conform/report/page.h"

namespace conform {

// The fitted edge curve is drawn through this many points at most (equal arc-length steps).
constexpr std::size_t kProfileReportCurvePoints = 2000;

struct ProfileStraightFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d along = Eigen::Vector3d::UnitY();   // Ty
  Eigen::Vector3d across = Eigen::Vector3d::UnitX();  // Tx
  Eigen::Vector3d at(const Eigen::Vector2d& designed) const {
    return origin + designed.y() * along + designed.x() * across;
  }
};

struct ProfileFeatureFigure {
  std::string id;
  std::string type;
  std::vector<Eigen::Vector3d> nominal;                  // the sampled outline on the straight profile
  std::vector<Eigen::Vector3d> mapped;                   // the Result's mapped outline (the same points)
  Eigen::Vector2d designed = Eigen::Vector2d::Zero();    // (Tx, Ty): the centre, or the first vertex
  Eigen::Vector3d nominal_at = Eigen::Vector3d::Zero();  // that point on the straight profile
  Eigen::Vector3d mapped_at = Eigen::Vector3d::Zero();   // and where it is cut
  double displacement_mm = 0.0;                          // |mapped_at - nominal_at|
  double max_displacement_mm = 0.0;                      // over the outline and the centre
};

struct ProfileReportFigures {
  std::vector<Eigen::Vector3d> edge;         // measured points, as read (empty without keep_geometry)
  std::vector<Eigen::Vector3d> second_edge;  // as read, when given
  std::vector<Eigen::Vector3d> edge_curve;   // the chosen edge model, s = 0 .. L
  ProfileStraightFrame straight;
  std::vector<ProfileFeatureFigure> features;
};

ProfileReportFigures profile_report_figures(const ProfileJobResult& job);

// The page: header (inputs, options, verdict: ok, or the termination), the 3D view (edge points with a run with
// keep_geometry), the edge fit's figures and the per-feature table (cells tied to profile_json), the displacement
// along the profile. Page::date is left to the caller.
html::Page profile_report(const ProfileJobOptions& options, const ProfileJobResult& job);

}  // namespace conform
