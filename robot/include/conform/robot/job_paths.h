#pragma once
// The tool paths of conform's jobs, from the CSV files they already write, as full tool frames (tool_frames.h). Which
// column gives the tool axis, and its sign (docs/export.md, "Where the tool axis comes from"):
//
//   job            header (columns used)                         tool axis z (tool -> work)          segments
//   tube-joint     phi_rad,x_mm,y_mm,z_mm,dx,dy,dz,...  (cut/weld) +d (the file's direction, Eq. 10-11)  one, closed
//   saddle         i,theta_rad,x_mm,y_mm,z_mm,pose_rad,...        -cos(pose) z_P - sin(pose) n_p(theta)  one
//   sicp           x_mm,y_mm,z_mm,nx,ny,nz                        -n (n points out of the material)      one
//   profile        id,i,x_mm,y_mm,z_mm,nx,ny,nz,dx,dy,dz          -n (the web normal; d: hint)           one per id
//   weld-layers    layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz           -n (n points towards the torch)        one per pass
//   frames         x_mm,y_mm,z_mm,qw,qx,qy,qz [,segment,kind]     the quaternion's z (frames as given)   per segment
//
// The job is told by the header. The tube-joint path file (normals, no tool) is refused, naming the cut and weld files.

#include <string>

#include "conform/core/csv.h"
#include "conform/robot/tool_frames.h"

namespace conform {

// "tube-joint", "saddle", "sicp", "profile", "weld-layers", "frames" (frame columns, e.g. export's own csv). Throws
// conform::Error naming the file and the columns a path file needs when the header matches none.
std::string detect_path_job(const CsvTable& table);

// The table's tool frames, in the file's frame. Every column but the text ones (id, segment, kind) must hold numbers
// in every row, used or not. Throws conform::Error naming the file, line and column of a missing, non-numeric,
// non-finite or out-of-bounds value (csv.h), a zero tool axis, or a jump between consecutive points beyond
// options.max_jump_ratio times the segment's median step.
ToolPath tool_path_from_csv(const CsvTable& table, const ToolFrameOptions& options,
                            ToolFrameFigures* figures = nullptr);

}  // namespace conform
