#pragma once
// Parallel weld paths on a parametric surface (Simas, Dias & Guenther, "A scallop-height based algorithm to compute
// parallel paths on parametric surfaces"). From a reference path in parameter space:
//   along a path, steps of chord length 2 sqrt(delta (rho - delta)) for a chord error delta on a curve of radius rho
//   (Eq. 1-3; rho from the path's curvature in space, never below the normal curvature II/I of the surface);
//   across, the next path at lateral surface distance g from each point, g = dc on a flat surface,
//   R*/(R* + w) dc on a convex and (R* + w)/R* dc on a concave one (Eq. 5: w the torch distance, R* the radius of
//   normal curvature across the path), the parameter offset (du, dv) first to first order (Eq. 8-9) and then, where g
//   is not small against R*, by Newton's method on the exact constraint (Eq. 4/7: the chord of an arc g on the
//   normal section, perpendicular to the path);
//   loops that offsetting makes in concave regions are cut out where a new segment crosses an earlier one (the
//   paper's heuristic).
// Beyond the paper: the direction of travel is taken over +-dc/2 of path and g is averaged over +-dc/2 along it, so
// that ripples shorter than the spacing are not passed on, amplified, from one path to the next.
// The torch stands on the side of n = normal_sign (r_u x r_v): "convex" means the surface bends away from it.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/parametric_surface.h"

namespace conform {

struct ParallelPathOptions {
  double spacing_mm = 2.0;         // dc: path spacing measured at the torch, mm
  double torch_distance_mm = 0.0;  // w: torch-to-surface distance, mm (0: g = dc everywhere)
  double chord_error_mm = 0.05;    // delta: max distance between a step's chord and the path, mm
  double max_step_mm = 5.0;        // longest step where the path is nearly straight, mm
  double newton_ratio = 0.01;      // solve the exact offset by Newton where g / R* exceeds this
  int normal_sign = 1;             // +1: the torch is on the side of r_u x r_v; -1: on the other side
  int side = 1;                    // +1: next path to the left of the direction of travel (seen from r_u x r_v)
  int max_paths = 500;             // including the reference path
  ParameterDomain region{-1e300, 1e300, -1e300, 1e300};  // stop once a path has no point in this region

  bool IsValid(std::string* error) const;
};

struct SurfacePath {
  std::vector<Eigen::Vector2d> uv;      // parameters of each point
  std::vector<Eigen::Vector3d> points;  // r(uv), mm
  std::vector<double> spacing_mm;       // g at each point: the lateral distance to the next path (Eq. 5)
  double length_mm() const;
};

struct ParallelPathResult {
  bool ok = false;
  std::string termination = "not run";
  std::vector<SurfacePath> paths;  // the reference path first
  std::size_t loops_removed = 0;   // loops cut out (the paper's heuristic)
  std::size_t points_in_loops = 0;
  std::size_t newton_offsets = 0;  // offsets solved exactly (g not small against R*)
  double chord_error_mm_max = 0.0; // over every step of every path, measured on the path
};

// Eq. (5): the lateral distance g on the surface for spacing dc at the torch, torch distance w, and normal curvature
// k across the path (1/mm, negative where convex seen from the torch).
double lateral_spacing(double spacing_mm, double torch_distance_mm, double normal_curvature);

// Eq. (1): the longest chord whose sagitta on a circle of radius rho is delta (rho <= delta: delta).
double chord_for_error(double chord_error_mm, double radius_mm);

// A smooth path through a parameter polyline (Catmull-Rom in (u, v)), stepped by Eq. (1-3) and checked: a step whose
// measured chord error exceeds delta is halved. *chord_error_max gets the largest measured error.
SurfacePath step_along(const ParametricSurface& surface, const std::vector<Eigen::Vector2d>& polyline,
                       const ParallelPathOptions& options, double* chord_error_max);

// The point at lateral distance g (Eq. 5, returned in *g) from r(uv) across the direction (du, dv) of travel; false
// when it falls outside the surface's domain. *exact tells whether Newton refined it.
bool offset_point(const ParametricSurface& surface, const Eigen::Vector2d& uv, const Eigen::Vector2d& direction,
                  const ParallelPathOptions& options, Eigen::Vector2d* out, double* g, bool* exact);
// As offset_point, at the given lateral distance *g when it is > 0 (Eq. 5 otherwise).
bool offset_point_by(const ParametricSurface& surface, const Eigen::Vector2d& uv, const Eigen::Vector2d& direction,
                     const ParallelPathOptions& options, Eigen::Vector2d* out, double* g, bool* exact);

// Cuts out every loop of a parameter polyline: where a segment crosses an earlier (non-adjacent) one, the points in
// between are deleted and the crossing point kept. *loops, *points count what was removed.
std::vector<Eigen::Vector2d> remove_loops(const std::vector<Eigen::Vector2d>& polyline, std::size_t* loops,
                                          std::size_t* points);
// Cuts every point where the polyline turns back by more than 90 degrees (a cusp: the bead would reverse on itself)
// or repeats its predecessor, until none is left; uv (same length) loses the same points. Returns how many.
std::size_t remove_cusps(std::vector<Eigen::Vector3d>* points, std::vector<Eigen::Vector2d>* uv);
// Whether two non-adjacent segments of the polyline cross.
bool self_intersects(const std::vector<Eigen::Vector2d>& polyline);

// The largest relative spacing error, %: for each point of `from` accepted by `counted` (all when empty), the
// distance d to the next path `to` (its smooth curve, densified) against the point's target g: |d - g| / g x 100.
// Points whose nearest point on `to` is one of its ends are skipped (the paths' ends drift apart). -1 when none.
double spacing_error_pct_max(const ParametricSurface& surface, const SurfacePath& from, const SurfacePath& to,
                             const std::function<bool(const Eigen::Vector2d&)>& counted = {});

// The reference path through `reference` (parameter polyline) and its parallels, until one leaves options.region or
// max_paths are made. Throws conform::Error when the options are not valid or the reference has < 2 points.
ParallelPathResult parallel_paths(const ParametricSurface& surface, const std::vector<Eigen::Vector2d>& reference,
                                  const ParallelPathOptions& options);

}  // namespace conform
