#pragma once
// Robot and CNC programs from tool frames (`conform export`, docs/export.md): one writer per format, each returning
// the text of its files; the caller writes them (atomically, apps/). The same path and options give the same bytes.
//
//   krl       KUKA KRL .src: LIN {X, Y, Z, A, B, C}, A B C in degrees (Z-Y'-X'')
//   rapid     ABB RAPID .mod: robtargets [[x,y,z],[q1,q2,q3,q4],...] (q1 scalar), MoveL
//   urscript  Universal Robots .script: movel(p[x,y,z,rx,ry,rz]) in metres and a rotation vector (rad)
//   fanuc     FANUC TP .ls: L P[n] with X, Y, Z, W, P, R (W, P, R = C, B, A of Z-Y'-X'')
//   val3      Staubli VAL3: point data (.dtx: x, y, z, rx, ry, rz, X-Y'-Z'') and a program (.pgx) walking it
//   gcode     ISO G-code .nc: 3-axis G1 X Y Z, or 5-axis Siemens TRAORI with A3= B3= C3= (tool vector), F in mm/min
//   csv       i,segment,kind,x_mm,y_mm,z_mm,qw,qx,qy,qz,a_deg,b_deg,c_deg

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/robot/tool_frames.h"

namespace conform {

struct ProgramOptions {
  Eigen::Isometry3d T_base_part = Eigen::Isometry3d::Identity();  // places the path (part frame) in the robot base
  double speed_mm_s = 10.0;                                       // along the path, mm/s
  double approach_speed_mm_s = 50.0;                              // approach and retract moves, mm/s
  double approach_mm = 50.0;          // approach and retract distance along -z (back along the tool axis), mm; 0: none
  std::string name = "conform_path";  // program / module name (letters, digits, '_'; starts with a letter)
  std::string tool;                   // tool name (format's default when empty: tool0, TOOL_DATA[1], UT 1, tTool)
  std::string work_object;            // work object / base (wobj0, BASE_DATA[1], UF 1, fPart)
  // Controller limit: most motion points per file; a longer program is split into parts called from the main file
  // (krl, rapid, fanuc). 0: the format's default (krl 2000, rapid 2000, fanuc 1000); never split for val3 (one
  // point array), urscript, gcode, csv.
  std::size_t max_points = 0;
  bool five_axis = true;  // gcode: TRAORI with tool vectors; false: 3-axis positions only
  // Blending through the interior points of a path, mm: the controller may leave each point this far before it and
  // join the next move (krl $APO.CDIS with C_DIS, rapid a zonedata zPath, urscript movel r=, val3 leave and reach;
  // fanuc CNT100 and gcode's continuous-path mode take no distance). 0: every point reached exactly (stops). The
  // first and last points of a path, the approach and the retract are always reached exactly.
  double blend_mm = 0.5;
  // One line each, written after the first point of each path is reached and before its retract: arc on / off,
  // spindle, dispenser (the format's own syntax, as the controller takes it). Empty: none. No control characters.
  std::string process_on;
  std::string process_off;
  // A joint position (six axes, deg) the robot moves to by a joint move before the first path and after the last:
  // KRL PTP {A1 .. A6}, RAPID MoveAbsJ, URScript movej (radians), FANUC J to a joint-represented P[], VAL3 movej to
  // a jointRx. Empty: none. Not for gcode or csv (no robot joints).
  std::vector<double> home_deg;
  std::string source;  // written into the header comment (the input file)

  bool IsValid(std::string* error) const;
};

enum class MoveKind { kApproach, kPath, kRetract };

// One motion point in the base frame.
struct RobotTarget {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: tool x, y, z in the base frame
  MoveKind kind = MoveKind::kPath;
  std::size_t segment = 0;
};

struct ProgramFile {
  std::string name;  // file name, no directory: the main file is `<name><ext>`, parts `<name>_<k><ext>`
  std::string text;
};

struct Program {
  std::vector<ProgramFile> files;  // the main file first
  std::size_t targets = 0;
  std::size_t parts = 1;
};

// "krl", "rapid", "urscript", "fanuc", "val3", "gcode", "csv".
const std::vector<std::string>& program_formats();
// ".src", ".mod", ".script", ".ls", ".pgx", ".nc", ".csv".
std::string program_extension(const std::string& format);

// The path in the base frame with approach and retract moves: per segment, approach at -approach_mm along the first
// frame's z, the frames, retract along the last frame's z.
std::vector<RobotTarget> plan_targets(const ToolPath& path, const ProgramOptions& options);

// Throws conform::Error on invalid options or an unknown format.
Program write_program(const ToolPath& path, const std::string& format, const ProgramOptions& options);

}  // namespace conform
