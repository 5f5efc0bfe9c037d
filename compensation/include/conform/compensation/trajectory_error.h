#pragma once
// How far a compensated trajectory is from the truth, and how smooth its correction is: the figures `conform sicp`
// reports when the ground truth is known (generated panels) and the S-ICP tests assert.

#include <cstddef>

#include "conform/compensation/trajectory.h"

namespace conform {

struct TrajectoryError {
  // Distance of each compensated point to the true path (the polyline through the truth's rows, closed when its ends
  // meet): what decides where the tool cuts. A slide along the path does not count here; on a straight or circular
  // edge no registration can see it (the scan looks the same), and the tool follows the edge all the same.
  double path_mean_mm = 0.0;
  double path_max_mm = 0.0;
  // Row by row, |p_i - truth_i|: includes the slide along the path.
  double mean_mm = 0.0;
  double rms_mm = 0.0;
  double max_mm = 0.0;
  std::size_t worst_row = 0;     // 0-based
  double normal_mean_deg = 0.0;  // angle between tool normals
  double normal_max_deg = 0.0;
  // The largest change of the correction (p_i - nominal_i) from one row to the next, mm: a jump at a segment
  // junction shows here. Compare with the truth's own (truth_step_mm), which is what a smooth deformation gives.
  double max_step_mm = 0.0;
  double truth_step_mm = 0.0;
  // The largest turn of the tool normal from one row to the next, degrees, and the truth's own.
  double normal_step_max_deg = 0.0;
  double truth_normal_step_max_deg = 0.0;
};

// The three trajectories must have the same number of rows (conform::Error otherwise).
TrajectoryError trajectory_error(const Trajectory& estimate, const Trajectory& truth, const Trajectory& nominal);

}  // namespace conform
