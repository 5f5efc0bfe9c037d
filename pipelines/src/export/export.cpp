#include "conform/pipelines/export/export.h"

#include <filesystem>

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/output_set.h"
#include "conform/core/transform_io.h"

namespace conform {
namespace {

// The figures of a later file's frames added to those of the files before it (`frames_before` frames).
void add_figures(const ToolFrameFigures& later, std::size_t frames_before, ToolFrameFigures& all) {
  if (later.max_orientation_step_rad > all.max_orientation_step_rad) {
    all.max_orientation_step_rad = later.max_orientation_step_rad;
    all.max_step_index = frames_before + later.max_step_index;
  }
  all.parallel_tangents += later.parallel_tangents;
  all.repeated_points += later.repeated_points;
  all.roll_limited += later.roll_limited;
}

// The files' paths in order, one program's segments.
ToolPath read_paths(const ExportJobOptions& options, ExportJobResult& result) {
  ToolPath all;
  for (const std::string& file : options.path_csvs) {
    ToolFrameFigures figures;
    ToolPath path = tool_path_from_csv(read_csv(file), options.frames, &figures);
    add_figures(figures, all.frames(), result.figures);
    if (result.files.empty() || result.files.back().job != path.job) all.job += (all.job.empty() ? "" : "+") + path.job;
    result.files.push_back({file, path.job, path.segments.size(), path.frames()});
    for (ToolSegment& segment : path.segments) all.segments.push_back(std::move(segment));
  }
  return all;
}

}  // namespace

ExportJobResult run_export(const ExportJobOptions& options) {
  std::string why;
  if (!options.frames.IsValid(&why)) throw Error("export: " + why);
  if (options.out_path.empty()) throw Error("export: no output file given");
  if (options.path_csvs.empty()) throw Error("export: no path file given");
  ProgramOptions program = options.program;
  const std::filesystem::path out(options.out_path);
  const bool named = !program.name.empty();
  if (!named) program.name = out.stem().string();
  if (!options.frame_path.empty()) program.T_base_part = read_transform(options.frame_path);
  if (program.source.empty()) {
    for (const std::string& file : options.path_csvs) {
      program.source += (program.source.empty() ? "" : ", ") + std::filesystem::path(file).filename().string();
    }
  }
  if (!program.IsValid(&why))
    throw Error("export: " + why + (named ? "" : " (the name is the output's stem; give one)"));
  program_extension(options.format);  // an unknown format before any reading

  ExportJobResult result;
  const ToolPath path = read_paths(options, result);
  const Program written = write_program(path, options.format, program);
  // All files or none, also when called outside a command's set.
  OutputSet files;
  for (std::size_t i = 0; i < written.files.size(); ++i) {
    const std::string target = i == 0 ? options.out_path : (out.parent_path() / written.files[i].name).string();
    write_file_atomically(target, written.files[i].text);
    result.written.push_back(target);
  }
  files.commit();
  result.job = path.job;
  result.segments = path.segments.size();
  result.frames = path.frames();
  result.targets = written.targets;
  result.parts = written.parts;
  result.T_base_part = program.T_base_part;
  return result;
}

}  // namespace conform
