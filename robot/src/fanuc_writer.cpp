// FANUC TP (.ls, ASCII for the offline converter): L P[n] moves, positions X Y Z (mm) and W P R (deg): rotations about
// the fixed x, y, z axes in that order, i.e. R = Rz(R) Ry(P) Rx(W) (the Z-Y'-X'' angles of KUKA, C B A).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "conform/core/error.h"
#include "conform/robot/robot_angles.h"
#include "program_writers.h"

namespace conform::detail {
namespace {

constexpr std::size_t kFanucMaxPoints = 1000;

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

// UT and UF are numbers on a FANUC.
std::string frame_number(const std::string& given, const char* what) {
  if (given.empty()) return "1";
  if (given.size() > 2 || !std::all_of(given.begin(), given.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    throw Error(std::string("export: fanuc ") + what + " must be a frame number (0 to 10), got '" + given + "'");
  }
  return given;
}

// A process line as a TP instruction: " <line> ;" (its own ';' kept).
std::string tp_line(const std::string& line) { return " " + line + (!line.empty() && line.back() == ';' ? "" : " ;"); }

std::string program(const std::string& name, const std::string& comment, const std::vector<std::string>& given,
                    const std::string& positions) {
  // A move may carry process lines after it ('\n'-separated): each is numbered as a line of its own.
  std::vector<std::string> lines;
  for (const std::string& g : given) {
    std::size_t start = 0;
    for (std::size_t end = g.find('\n'); end != std::string::npos; start = end + 1, end = g.find('\n', start)) {
      lines.push_back(g.substr(start, end - start));
    }
    lines.push_back(g.substr(start));
  }
  std::string text =
      "/PROG  " + upper(name) + "\n/ATTR\nCOMMENT\t\t= \"" + comment + "\";\nDEFAULT_GROUP\t= 1,*,*,*,*;\n/MN\n";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string number = std::to_string(i + 1);
    text += std::string(number.size() < 4 ? 4 - number.size() : 0, ' ') + number + ":" + lines[i] + "\n";
  }
  return text + "/POS\n" + positions + "/END\n";
}

}  // namespace

Program write_fanuc(const std::vector<RobotTarget>& targets, const ProgramOptions& options) {
  const std::string ut = frame_number(options.tool, "tool (UT)");
  const std::string uf = frame_number(options.work_object, "work object (UF)");
  const auto parts = parts_of(targets.size(), options.max_points == 0 ? kFanucMaxPoints : options.max_points);
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  std::vector<std::string> moves(targets.size());
  std::vector<std::string> positions(targets.size());
  std::size_t local = 0;
  std::size_t part = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (i == parts[part].second) ++part;
    local = i - parts[part].first + 1;  // P[] numbers start at 1 in every program
    const RobotTarget& t = targets[i];
    abc = euler_zyx_deg(t.rotation, i == 0 ? nullptr : &abc);
    const bool path = t.kind == MoveKind::kPath;
    const double speed = path ? options.speed_mm_s : options.approach_speed_mm_s;
    // TP speeds are whole mm/sec, at least 1. CNT is a share of the corner, not a distance.
    // The approach point by a joint move at the joints' full speed share (the robot comes from anywhere), the path
    // and the retract linear.
    moves[i] = t.kind == MoveKind::kApproach
                   ? "J P[" + std::to_string(local) + "] 100% FINE ;"
                   : "L P[" + std::to_string(local) + "] " + num(std::max(1.0, std::round(speed)), 0) + "mm/sec " +
                         (blends(targets, i, options) ? "CNT100" : "FINE") + " ;";
    if (starts_path(targets, i) && !options.process_on.empty()) moves[i] += "\n" + tp_line(options.process_on);
    if (ends_path(targets, i) && !options.process_off.empty()) moves[i] += "\n" + tp_line(options.process_off);
    const Eigen::Vector3d& p = t.position_mm;
    positions[i] = "P[" + std::to_string(local) + "]{\n   GP1:\n\tUF : " + uf + ", UT : " + ut +
                   ",\t\tCONFIG : 'N U T, 0, 0, 0',\n\tX = " + num(p.x(), 6) + "  mm,\tY = " + num(p.y(), 6) +
                   "  mm,\tZ = " + num(p.z(), 6) + "  mm,\n\tW = " + num(abc(2), 9) + " deg,\tP = " + num(abc(1), 9) +
                   " deg,\tR = " + num(abc(0), 9) + " deg\n};\n";
  }
  Program out;
  out.parts = parts.size();
  const std::string head = " UFRAME_NUM=" + uf + " ;";
  const std::string tool = " UTOOL_NUM=" + ut + " ;";
  std::vector<std::string> main_lines = {head, tool};
  // The home position: a joint-represented P[] of the main file, after its other points.
  const std::size_t home_index = (parts.size() == 1 ? targets.size() : 0) + 1;
  std::string home_move, home_position;
  if (!options.home_deg.empty()) {
    const std::vector<double>& j = options.home_deg;
    home_move = "J P[" + std::to_string(home_index) + "] 100% FINE ;";
    home_position = "P[" + std::to_string(home_index) + "]{\n   GP1:\n\tUF : " + uf + ", UT : " + ut +
                    ",\n\tJ1 = " + num(j[0], 6) + " deg,\tJ2 = " + num(j[1], 6) + " deg,\tJ3 = " + num(j[2], 6) +
                    " deg,\n\tJ4 = " + num(j[3], 6) + " deg,\tJ5 = " + num(j[4], 6) + " deg,\tJ6 = " + num(j[5], 6) +
                    " deg\n};\n";
    main_lines.push_back(home_move);
  }
  if (parts.size() == 1) {
    main_lines.insert(main_lines.end(), moves.begin(), moves.end());
    if (!home_move.empty()) main_lines.push_back(home_move);
    std::string pos;
    for (const std::string& p : positions) pos += p;
    out.files.push_back(
        {options.name + ".ls", program(options.name, "conform export", main_lines, pos + home_position)});
    return out;
  }
  for (std::size_t k = 0; k < parts.size(); ++k) {
    main_lines.push_back(" CALL " + upper(options.name) + "_" + std::to_string(k + 1) + " ;");
  }
  if (!home_move.empty()) main_lines.push_back(home_move);
  out.files.push_back({options.name + ".ls", program(options.name, "conform export", main_lines, home_position)});
  for (std::size_t k = 0; k < parts.size(); ++k) {
    std::vector<std::string> lines = {head, tool};
    std::string pos;
    for (std::size_t i = parts[k].first; i < parts[k].second; ++i) {
      lines.push_back(moves[i]);
      pos += positions[i];
    }
    const std::string name = options.name + "_" + std::to_string(k + 1);
    out.files.push_back({name + ".ls", program(name, "conform part", lines, pos)});
  }
  return out;
}

}  // namespace conform::detail
