#pragma once
// `conform export`: a job's path CSV as a robot or CNC program with full tool frames (docs/export.md;
// robot/job_paths.h, tool_frames.h, robot_program.h).

#include <cstddef>
#include <string>
#include <vector>

#include "conform/robot/job_paths.h"
#include "conform/robot/robot_program.h"

namespace conform {

struct ExportJobOptions {
  // The jobs' path files, in program order (a tube joint's cut then its weld, the layers of several weld-layers
  // files): each file's paths follow the previous file's, with the retract and approach between paths as within one
  // file. At least one.
  std::vector<std::string> path_csvs;
  std::string format;      // program_formats(); required
  std::string out_path;    // the main program file; the others go beside it under their own names; required
  std::string frame_path;  // T_base_part, 4x4 text; empty: program.T_base_part as given (identity by default)
  ToolFrameOptions frames;
  ProgramOptions program;  // an empty program.name is taken from out_path's stem
};

// One path file of a program.
struct ExportPathFile {
  std::string path;
  std::string job;  // which job's file it is
  std::size_t segments = 0;
  std::size_t frames = 0;
};

struct ExportJobResult {
  std::string job;  // which job's file it was; several: their jobs in order, '+' between distinct neighbours
  std::vector<ExportPathFile> files;
  std::size_t segments = 0;
  std::size_t frames = 0;
  std::size_t targets = 0;  // motion points, with approach and retract
  std::size_t parts = 1;
  ToolFrameFigures figures;
  Eigen::Isometry3d T_base_part = Eigen::Isometry3d::Identity();
  std::vector<std::string> written;  // every file, the main one first
};

// Throws conform::Error naming the file and the problem (not a path file, a bad value, a frame file that is not rigid,
// a bad option); nothing is written then. The files are written atomically, all or none (with the current OutputSet).
ExportJobResult run_export(const ExportJobOptions& options);

}  // namespace conform
