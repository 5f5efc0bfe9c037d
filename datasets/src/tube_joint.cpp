#include "conform/datasets/tube_joint.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/datasets/tube.h"
#include "conform/datasets/tube_surface.h"

namespace conform {
namespace {

// The stub as generate_tube makes it for a length: a closed inner tube whose middle is at z_S = length / 2, its
// bumps moved from z_S into that tube frame, so that the surface in S does not depend on the length.
TubeOptions stub_tube(const TubeJointOptions& o, double length) {
  TubeOptions stub = o.stub;
  stub.length_mm = length;
  stub.arc_rad = 2.0 * kPi;
  stub.arc_center_rad = 0.0;
  stub.surface = TubeSurface::kInner;
  stub.T_world_tube = Eigen::Translation3d(0.0, 0.0, 0.5 * length) * Eigen::Isometry3d::Identity();
  for (TubeBump& bump : stub.bumps) bump.z_mm -= 0.5 * length;
  return stub;
}

// f(z) of the header: > 0 while the stub's wall point is outside the leg.
double outside(const TubeJointOptions& o, const TubeOptions& stub, const Eigen::Isometry3d& T_S_tube, double phi,
               double z_S) {
  const Eigen::Vector3d s = T_S_tube * tube_surface_in_tube(stub, phi, z_S - 0.5 * stub.length_mm).point;
  const Eigen::Vector3d q = o.T_L_S * s;
  return q.head<2>().norm() - tube_radius(o.leg, std::atan2(q.y(), q.x()), q.z());
}

double root(const TubeJointOptions& o, const TubeOptions& stub, const Eigen::Isometry3d& T_S_tube, double phi) {
  const double length = stub.length_mm;
  const double step = std::min(1.0, length / 1000.0);
  double z0 = 0.0;
  double f0 = outside(o, stub, T_S_tube, phi, z0);
  if (!(f0 > 0.0)) {
    std::ostringstream why;
    why << "tube joint: the stub's distal end is already inside the leg at azimuth " << phi * 180.0 / kPi
        << " deg: increase the protrusion";
    throw Error(why.str());
  }
  for (double z1 = step; z1 <= length + 0.5 * step; z1 += step) {
    const double f1 = outside(o, stub, T_S_tube, phi, std::min(z1, length));
    if (f1 <= 0.0) {
      double lo = z0;
      double hi = std::min(z1, length);
      for (int i = 0; i < 100 && hi - lo > 1e-10; ++i) {
        const double mid = 0.5 * (lo + hi);
        (outside(o, stub, T_S_tube, phi, mid) > 0.0 ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
    z0 = z1;
  }
  std::ostringstream why;
  why << "tube joint: the stub does not reach the leg at azimuth " << phi * 180.0 / kPi
      << " deg: the protrusion, pitch, offset or radii do not make a joint";
  throw Error(why.str());
}

}  // namespace

bool TubeJointOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(std::isfinite(protrusion_mm) && protrusion_mm > 0.0))
    why << "protrusion " << protrusion_mm << " mm must be > 0";
  else if (!(leg.radius_mm > stub.radius_mm))
    why << "the leg radius must exceed the stub's inner radius";
  else if (leg.bow_mm != 0.0 || stub.bow_mm != 0.0)
    why << "bow is not supported for a tube joint";
  else if (!(stub_length_mm >= 0.0 && leg_length_mm >= 0.0 && leg_margin_mm >= 0.0))
    why << "lengths must be >= 0";
  else if (!(leg_arc_rad >= 0.0 && leg_arc_rad <= 2.0 * kPi))
    why << "leg arc must be in [0, 360] deg";
  else if (truth_points < 8)
    why << "truth points " << truth_points << " must be >= 8";
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

TubeJointTruth tube_joint_truth(const TubeJointOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tube joint: " + why);
  TubeJointTruth truth;
  truth.stub = stub_tube(options, options.stub_length_mm > 0.0 ? options.stub_length_mm : options.protrusion_mm);
  truth.T_S_stub_tube = truth.stub.T_world_tube;
  double theta_min = std::numeric_limits<double>::infinity();
  double theta_max = -theta_min;
  double z_extent = 0.0;
  for (int k = 0; k < options.truth_points; ++k) {
    const double phi = 2.0 * kPi * k / options.truth_points;
    const double z = root(options, truth.stub, truth.T_S_stub_tube, phi);
    const Eigen::Vector3d p =
        truth.T_S_stub_tube * tube_surface_in_tube(truth.stub, phi, z - 0.5 * truth.stub.length_mm).point;
    truth.phi_rad.push_back(phi);
    truth.points.push_back(p);
    truth.stub_z_mm.push_back(z);
    const Eigen::Vector3d q = options.T_L_S * p;
    theta_min = std::min(theta_min, std::atan2(q.y(), q.x()));
    theta_max = std::max(theta_max, std::atan2(q.y(), q.x()));
    z_extent = std::max(z_extent, std::abs(q.z()));
  }
  if (options.stub_length_mm == 0.0) {
    const double deepest = *std::max_element(truth.stub_z_mm.begin(), truth.stub_z_mm.end());
    const double length = std::min(options.protrusion_mm, deepest + options.leg_margin_mm);
    bool inside = true;
    for (int k = 0; k < 360 && inside; ++k) {
      inside = outside(options, truth.stub, truth.T_S_stub_tube, 2.0 * kPi * k / 360.0, length) < 0.0;
    }
    truth.stub = stub_tube(options, inside ? length : options.protrusion_mm);
    truth.T_S_stub_tube = truth.stub.T_world_tube;
  }
  truth.leg = options.leg;
  truth.leg.surface = TubeSurface::kOuter;
  truth.leg.T_world_tube = Eigen::Isometry3d::Identity();
  truth.leg.length_mm = options.leg_length_mm > 0.0 ? options.leg_length_mm : 2.0 * (z_extent + options.leg_margin_mm);
  const double margin_rad = options.leg_margin_mm / options.leg.radius_mm;
  truth.leg.arc_rad =
      options.leg_arc_rad > 0.0 ? options.leg_arc_rad : std::min(2.0 * kPi, theta_max - theta_min + 2.0 * margin_rad);
  truth.leg.arc_center_rad = options.leg_arc_rad > 0.0 ? 0.0 : 0.5 * (theta_min + theta_max);
  return truth;
}

TubeJointScans generate_tube_joint(const TubeJointOptions& options) {
  TubeJointScans scans;
  scans.truth = tube_joint_truth(options);
  TubeOptions leg = scans.truth.leg;
  TubeOptions stub = scans.truth.stub;
  stub.seed = options.stub.seed;
  scans.leg_L = generate_tube(leg).mesh;
  scans.stub_S = generate_tube(stub).mesh;
  return scans;
}

double leg_surface_distance(const TubeJointTruth& truth, const Eigen::Isometry3d& T_L_S, const Eigen::Vector3d& p_S) {
  const Eigen::Vector3d q = T_L_S * p_S;
  return q.head<2>().norm() - tube_radius(truth.leg, std::atan2(q.y(), q.x()), q.z());
}

double distance_to_truth(const TubeJointTruth& truth, const Eigen::Vector3d& p_S) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = truth.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = truth.points[i];
    const Eigen::Vector3d& b = truth.points[(i + 1) % n];
    const Eigen::Vector3d ab = b - a;
    const double t = std::clamp((p_S - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (p_S - (a + t * ab)).norm());
  }
  return best;
}

}  // namespace conform
