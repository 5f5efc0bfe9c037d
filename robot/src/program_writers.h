#pragma once
// The writers behind write_program() (robot_program.h), one file each, and what they share.

#include <string>
#include <utility>
#include <vector>

#include "conform/robot/robot_program.h"

namespace conform::detail {

Program write_krl(const std::vector<RobotTarget>& targets, const ProgramOptions& options);
Program write_rapid(const std::vector<RobotTarget>& targets, const ProgramOptions& options);
Program write_urscript(const std::vector<RobotTarget>& targets, const ProgramOptions& options);
Program write_fanuc(const std::vector<RobotTarget>& targets, const ProgramOptions& options);
Program write_val3(const std::vector<RobotTarget>& targets, const ProgramOptions& options);
Program write_gcode(const std::vector<RobotTarget>& targets, const ProgramOptions& options);
Program write_frames_csv(const std::vector<RobotTarget>& targets, const ProgramOptions& options);

// Fixed decimals, '.' whatever the locale, no "-0".
std::string num(double value, int decimals);
// [begin, end) index ranges of at most `max` targets each (one range when max is 0).
std::vector<std::pair<std::size_t, std::size_t>> parts_of(std::size_t count, std::size_t max);
// `options.tool` or `fallback` when empty (same for the work object).
std::string tool_or(const ProgramOptions& options, const std::string& fallback);
std::string work_object_or(const ProgramOptions& options, const std::string& fallback);
// Whether targets[i] is the first (the last) point of a path: reached exactly, the process line starts after it
// (stops after it; ProgramOptions::process_on, process_off).
bool starts_path(const std::vector<RobotTarget>& targets, std::size_t i);
bool ends_path(const std::vector<RobotTarget>& targets, std::size_t i);
// Whether the move to targets[i] blends into the next: an interior point of a path, with a blend distance.
bool blends(const std::vector<RobotTarget>& targets, std::size_t i, const ProgramOptions& options);
// One line saying where the program came from, for a comment.
std::string provenance(const ProgramOptions& options, std::size_t targets);

}  // namespace conform::detail
