#include "conform/pipelines/export.h"

#include <filesystem>

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/output_set.h"
#include "conform/core/transform_io.h"

namespace conform {

ExportJobResult run_export(const ExportJobOptions& options) {
  std::string why;
  if (!options.frames.IsValid(&why)) throw Error("export: " + why);
  if (options.out_path.empty()) throw Error("export: no output file given");
  ProgramOptions program = options.program;
  const std::filesystem::path out(options.out_path);
  const bool named = !program.name.empty();
  if (!named) program.name = out.stem().string();
  if (!options.frame_path.empty()) program.T_base_part = read_transform(options.frame_path);
  if (program.source.empty()) program.source = std::filesystem::path(options.path_csv).filename().string();
  if (!program.IsValid(&why))
    throw Error("export: " + why + (named ? "" : " (the name is the output's stem; give one)"));
  program_extension(options.format);  // an unknown format before any reading

  ExportJobResult result;
  const ToolPath path = tool_path_from_csv(read_csv(options.path_csv), options.frames, &result.figures);
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
