#pragma once
// The geometry behind a generated panel (panel_options.h): the nominal surface over its parameter plane, the
// opening's edge in that plane, and the known deformation. Public so that tests can check the generator against it.

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/datasets/panel_options.h"

namespace conform {

// A point of the opening's edge in the parameter plane: q = (x, y) for the plate, (x, s) for the nose cone.
struct OpeningSample {
  Eigen::Vector2d q = Eigen::Vector2d::Zero();
  Eigen::Vector2d m = Eigen::Vector2d::Zero();  // unit, away from the opening into the material
  double tau = 0.0;  // mesh parameter: the edge's length plus band / 2 times the turn of m (fans at sharp corners)
};

// The nominal surface and its unit normal (plate: towards +z; nose cone: away from the barrel's axis).
Eigen::Vector3d panel_surface(const PanelOptions& options, const Eigen::Vector2d& q);
Eigen::Vector3d panel_normal(const PanelOptions& options, const Eigen::Vector2d& q);

// The opening's edge, counter-clockwise in the parameter plane, sampled densely (about every step_mm, and every
// 2 degrees of turn); the first sample is not repeated at the end. tau of the first sample is 0.
std::vector<OpeningSample> opening_edge(const PanelOptions& options, double step_mm);
// The sample at mesh parameter tau (wrapped into [0, total)), interpolated linearly; m renormalised.
OpeningSample edge_at(const std::vector<OpeningSample>& edge, double total_tau, double tau);

// The known deformation: p (nominal, panel frame) -> G * (p + D(p)).
Eigen::Vector3d deform_point(const PanelOptions& options, const Eigen::Vector3d& p);
// The deformed image of a unit normal n at p: the inverse transpose of the map's Jacobian (central differences),
// normalised.
Eigen::Vector3d deform_normal(const PanelOptions& options, const Eigen::Vector3d& p, const Eigen::Vector3d& n);
// G, the rigid part.
Eigen::Isometry3d panel_rigid_motion(const PanelOptions& options);

}  // namespace conform
