// The program writers (robot/robot_program.h) and their angle conventions (robot_angles.h): known frames written
// in every format and parsed back here by a parser that rebuilds the rotation from the vendors' definitions, written
// out below by hand (not by calling the writer's conversions). Positions to 1e-6 mm, axes to 1e-9 rad.

#include <cmath>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/robot/robot_program.h"
#include "hand_rotations.h"

namespace conform {
namespace {

using namespace test;  // hand_rotations.h

constexpr double kPositionTol = 1e-6;  // mm

struct Parsed {
  Eigen::Vector3d position;
  Eigen::Matrix3d rotation;  // for gcode only the z column is meaningful
};

std::vector<double> numbers(const std::smatch& m) {
  std::vector<double> out;
  for (std::size_t i = 1; i < m.size(); ++i) out.push_back(std::stod(m[i].str()));
  return out;
}

std::vector<std::vector<double>> all_matches(const std::string& text, const std::string& pattern) {
  std::vector<std::vector<double>> out;
  const std::regex re(pattern);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
    out.push_back(numbers(*it));
  }
  return out;
}

const std::string N = "(-?[0-9]+\\.?[0-9]*(?:[eE][-+]?[0-9]+)?)";

// Per format: the motion points of the program text, in order.
std::vector<Parsed> parse(const std::string& format, const std::string& text) {
  std::vector<Parsed> out;
  if (format == "krl") {
    for (const auto& v : all_matches(
             text, "(?:LIN|PTP) \\{X " + N + ", Y " + N + ", Z " + N + ", A " + N + ", B " + N + ", C " + N + "\\}")) {
      out.push_back({{v[0], v[1], v[2]}, Rz(rad(v[3])) * Ry(rad(v[4])) * Rx(rad(v[5]))});
    }
  } else if (format == "rapid") {
    for (const auto& v : all_matches(text, "robtarget p[0-9]+ := \\[\\[" + N + "," + N + "," + N + "\\],\\[" + N + "," +
                                               N + "," + N + "," + N + "\\]")) {
      out.push_back({{v[0], v[1], v[2]}, from_quaternion(v[3], v[4], v[5], v[6])});
    }
  } else if (format == "urscript") {
    for (const auto& v :
         all_matches(text, "move[lj]\\(p\\[" + N + ", " + N + ", " + N + ", " + N + ", " + N + ", " + N + "\\]")) {
      out.push_back({Eigen::Vector3d(v[0], v[1], v[2]) * 1000.0, from_rotation_vector({v[3], v[4], v[5]})});
    }
  } else if (format == "fanuc") {
    for (const auto& v : all_matches(text, "X = " + N + "  mm,\tY = " + N + "  mm,\tZ = " + N + "  mm,\n\tW = " + N +
                                               " deg,\tP = " + N + " deg,\tR = " + N + " deg")) {
      // W, P, R: about the fixed x, then y, then z: R = Rz(R) Ry(P) Rx(W).
      out.push_back({{v[0], v[1], v[2]}, Rz(rad(v[5])) * Ry(rad(v[4])) * Rx(rad(v[3]))});
    }
  } else if (format == "val3") {
    for (const auto& v : all_matches(text, "x=\"" + N + "\" y=\"" + N + "\" z=\"" + N + "\" rx=\"" + N + "\" ry=\"" +
                                               N + "\" rz=\"" + N + "\"")) {
      out.push_back({{v[0], v[1], v[2]}, Rx(rad(v[3])) * Ry(rad(v[4])) * Rz(rad(v[5]))});
    }
  } else if (format == "gcode") {
    for (const auto& v :
         all_matches(text, "G[01] X" + N + " Y" + N + " Z" + N + " A3=" + N + " B3=" + N + " C3=" + N)) {
      Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
      r.col(2) = -Eigen::Vector3d(v[3], v[4], v[5]);  // the tool vector points from the tip to the holder
      out.push_back({{v[0], v[1], v[2]}, r});
    }
  } else if (format == "csv") {
    for (const auto& v : all_matches(text, "\n[0-9]+,[0-9]+,[a-z]+," + N + "," + N + "," + N + "," + N + "," + N + "," +
                                               N + "," + N + "," + N + "," + N + "," + N)) {
      const Eigen::Matrix3d q = from_quaternion(v[3], v[4], v[5], v[6]);
      const Eigen::Matrix3d abc = Rz(rad(v[7])) * Ry(rad(v[8])) * Rx(rad(v[9]));
      EXPECT_LT(angle_between(q, abc), kAxisTol);
      out.push_back({{v[0], v[1], v[2]}, q});
    }
  }
  return out;
}

// The test's frames: identity, 90 deg about each axis, gimbal lock (B = +-90 deg with A and C both non-zero), and
// random frames from a seeded generator; positions spread over a robot's reach.
std::vector<ToolFrame> known_frames() {
  std::vector<Eigen::Matrix3d> rotations = {Eigen::Matrix3d::Identity(),
                                            Rx(kPi / 2),
                                            Ry(kPi / 2),
                                            Rz(kPi / 2),
                                            Rx(-kPi / 2),
                                            Rz(kPi),
                                            Rz(rad(30)) * Ry(kPi / 2) * Rx(rad(10)),
                                            Rz(rad(-40)) * Ry(-kPi / 2) * Rx(rad(25)),
                                            Rz(rad(30)) * Ry(kPi / 2 - 1e-9) * Rx(rad(10))};
  std::mt19937 rng(19);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 20; ++i) {
    Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    rotations.push_back(q.normalized().toRotationMatrix());
  }
  std::vector<ToolFrame> frames;
  std::uniform_real_distribution<double> reach(-1500.0, 1500.0);
  for (const Eigen::Matrix3d& r : rotations) {
    ToolFrame f;
    f.rotation = r;
    f.position = Eigen::Vector3d(reach(rng), reach(rng), reach(rng));
    frames.push_back(f);
  }
  return frames;
}

ToolPath path_of(const std::vector<ToolFrame>& frames) {
  ToolPath path;
  path.job = "test";
  path.segments.push_back({"s", frames});
  return path;
}

ProgramOptions no_approach() {
  ProgramOptions o;
  o.approach_mm = 0.0;
  o.name = "t";
  return o;
}

std::string all_text(const Program& p) {
  std::string text;
  for (const ProgramFile& f : p.files) text += f.text;
  return text;
}

TEST(RobotProgram, EveryFormatWritesKnownFramesThatParseBack) {
  const std::vector<ToolFrame> frames = known_frames();
  for (const std::string& format : program_formats()) {
    SCOPED_TRACE(format);
    const Program program = write_program(path_of(frames), format, no_approach());
    const std::vector<Parsed> parsed = parse(format, all_text(program));
    ASSERT_EQ(parsed.size(), frames.size());
    double worst_position = 0, worst_axis = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      worst_position = std::max(worst_position, (parsed[i].position - frames[i].position).norm());
      // gcode gives the tool axis only: the angle between the axes (atan2 of sine and cosine, exact near 0).
      const Eigen::Vector3d z = parsed[i].rotation.col(2), z_true = frames[i].rotation.col(2);
      const double axis = format == "gcode" ? std::atan2(z.cross(z_true).norm(), z.dot(z_true))
                                            : angle_between(parsed[i].rotation, frames[i].rotation);
      worst_axis = std::max(worst_axis, axis);
    }
    EXPECT_LT(worst_position, kPositionTol);
    EXPECT_LT(worst_axis, kAxisTol);
    std::printf("[ measured ] %-8s position %.2e mm, orientation %.2e rad\n", format.c_str(), worst_position,
                worst_axis);
  }
}

TEST(RobotProgram, TheFrameOptionPlacesThePathInTheBase) {
  // T_base_part: 90 deg about z and a shift; the identity frame at (100, 0, 0) lands at (10, 120, 30) turned by Rz.
  ProgramOptions o = no_approach();
  o.T_base_part = Eigen::Translation3d(10, 20, 30) * Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ());
  ToolFrame f;
  f.position = {100, 0, 0};
  const auto parsed = parse("krl", all_text(write_program(path_of({f}), "krl", o)));
  ASSERT_EQ(parsed.size(), 1u);
  EXPECT_LT((parsed[0].position - Eigen::Vector3d(10, 120, 30)).norm(), kPositionTol);
  EXPECT_LT(angle_between(parsed[0].rotation, Rz(kPi / 2)), kAxisTol);
}

TEST(RobotProgram, ApproachAndRetractAlongMinusZ) {
  ProgramOptions o = no_approach();
  o.approach_mm = 25;
  ToolFrame f;
  f.rotation = Ry(kPi / 2);  // z = +x of the base
  f.position = {0, 0, 0};
  std::vector<ToolFrame> frames = {f, f};
  frames[1].position = {0, 10, 0};
  const std::vector<RobotTarget> t = plan_targets(path_of(frames), o);
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0].kind, MoveKind::kApproach);
  EXPECT_LT((t[0].position_mm - Eigen::Vector3d(-25, 0, 0)).norm(), 1e-12);
  EXPECT_EQ(t[3].kind, MoveKind::kRetract);
  EXPECT_LT((t[3].position_mm - Eigen::Vector3d(-25, 10, 0)).norm(), 1e-12);
}

TEST(RobotProgram, LongProgramsAreSplitIntoPartsWithTheSameMoves) {
  std::vector<ToolFrame> frames = known_frames();
  for (const std::string format : {"krl", "rapid", "fanuc"}) {
    SCOPED_TRACE(format);
    ProgramOptions o = no_approach();
    const Program whole = write_program(path_of(frames), format, o);
    o.max_points = 8;
    const Program split = write_program(path_of(frames), format, o);
    const std::size_t parts = (frames.size() + 7) / 8;
    EXPECT_EQ(whole.parts, 1u);
    EXPECT_EQ(split.parts, parts);
    ASSERT_EQ(split.files.size(), parts + 1);
    EXPECT_EQ(split.files[1].name, "t_1" + program_extension(format));
    const auto a = parse(format, all_text(whole));
    const auto b = parse(format, all_text(split));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].position, b[i].position);
      EXPECT_EQ(a[i].rotation, b[i].rotation);
    }
    for (std::size_t k = 1; k <= parts; ++k) {
      EXPECT_LE(parse(format, split.files[k].text).size(), 8u);
      const std::string call = (format == "fanuc" ? "CALL T_" : "t_") + std::to_string(k);
      EXPECT_NE(split.files[0].text.find(call), std::string::npos) << call;
    }
  }
}

TEST(RobotProgram, SameInputSameBytesAndBadOptionsRefused) {
  const std::vector<ToolFrame> frames = known_frames();
  for (const std::string& format : program_formats()) {
    EXPECT_EQ(all_text(write_program(path_of(frames), format, {})),
              all_text(write_program(path_of(frames), format, {})));
  }
  ProgramOptions o;
  o.name = "9lives";
  EXPECT_THROW(write_program(path_of(frames), "krl", o), Error);
  o = {};
  o.tool = "t;\nbad";
  EXPECT_THROW(write_program(path_of(frames), "rapid", o), Error);
  o = {};
  o.T_base_part.linear() *= 2.0;
  EXPECT_THROW(write_program(path_of(frames), "krl", o), Error);
  o = {};
  o.speed_mm_s = std::nan("");
  EXPECT_THROW(write_program(path_of(frames), "krl", o), Error);
  EXPECT_THROW(write_program(path_of(frames), "abb", {}), Error);
  o = {};
  o.tool = "tool7";
  EXPECT_THROW(write_program(path_of(frames), "fanuc", o), Error);  // UT is a number
}

TEST(RobotProgram, AFileNameCannotEndAComment) {
  ProgramOptions o = no_approach();
  o.source = "a--b;c)\nLIN {X 1}<!--";
  const std::vector<ToolFrame> frames = known_frames();
  const Program val3 = write_program(path_of(frames), "val3", o);
  const std::string& dtx = val3.files[1].text;
  EXPECT_EQ(dtx.find("--", dtx.find("<!--") + 4), dtx.find("-->"));  // the comment's only "--" is its end
  const std::string krl = all_text(write_program(path_of(frames), "krl", o));
  EXPECT_EQ(parse("krl", krl).size(), frames.size());  // no extra LIN from the name
  EXPECT_EQ(krl.find("b;c"), std::string::npos);
}

// Two paths of five points each, with approach and retract.
ToolPath two_paths() {
  const std::vector<ToolFrame> frames = known_frames();
  ToolPath path;
  path.job = "test";
  path.segments.push_back({"a", std::vector<ToolFrame>(frames.begin(), frames.begin() + 5)});
  path.segments.push_back({"b", std::vector<ToolFrame>(frames.begin() + 5, frames.begin() + 10)});
  return path;
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The process lines: after the first point of each path is reached (the approach and that point before it) and
// after its last point, before the retract (every point of the path before it); once per path, in every format
// that runs a program.
TEST(RobotProgram, ProcessLinesAfterThePathsFirstPointAndBeforeItsRetract) {
  ProgramOptions o;
  o.name = "t";
  o.process_on = "PROCESS_ON_7";
  o.process_off = "PROCESS_OFF_7";
  for (const std::string format : {"krl", "rapid", "urscript", "fanuc", "val3", "gcode"}) {
    const Program p = write_program(two_paths(), format, o);
    const std::string& text = p.files[0].text;  // the program (val3: .pgx; points in the .dtx)
    ASSERT_EQ(count_of(text, "PROCESS_ON_7"), 2u) << format;
    ASSERT_EQ(count_of(text, "PROCESS_OFF_7"), 2u) << format;
    std::vector<std::size_t> on, off;
    for (std::size_t at = text.find("PROCESS_ON_7"); at != std::string::npos; at = text.find("PROCESS_ON_7", at + 1))
      on.push_back(at);
    for (std::size_t at = text.find("PROCESS_OFF_7"); at != std::string::npos; at = text.find("PROCESS_OFF_7", at + 1))
      off.push_back(at);
    // Motion points written before each line: approach + first point; then + the other 4 points; the second path
    // after the first path's retract (7 points) the same way.
    const auto moves_before = [&](std::size_t at) {
      const std::string head = text.substr(0, at);
      if (format == "val3") return count_of(head, "(pPath[");
      if (format == "fanuc") return count_of(head, "L P[") + count_of(head, "J P[");
      if (format == "rapid") return count_of(head, "MoveL ") + count_of(head, "MoveJ ");
      if (format == "gcode") return count_of(head, "G1 X") + count_of(head, "G0 X");
      return parse(format, head).size();
    };
    EXPECT_EQ(moves_before(on[0]), 2u) << format;
    EXPECT_EQ(moves_before(off[0]), 6u) << format;
    EXPECT_EQ(moves_before(on[1]), 9u) << format;
    EXPECT_EQ(moves_before(off[1]), 13u) << format;
  }
  o.process_on = "ARC_ON\nLIN {X 0}";
  EXPECT_THROW(write_program(two_paths(), "krl", o), Error);  // one line, no control characters
}

// The approach point of each path is reached by a joint move (the robot comes from anywhere), the path and the
// retract by straight lines; every point, the approach included, parses back to the planned target.
TEST(RobotProgram, ApproachByAJointMovePathAndRetractLinear) {
  ProgramOptions o;
  o.name = "t";
  const std::vector<RobotTarget> planned = plan_targets(two_paths(), o);
  ASSERT_EQ(planned.size(), 14u);
  const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> moves = {
      {"krl", {"PTP {", "LIN {"}}, {"rapid", {"MoveJ ", "MoveL "}}, {"urscript", {"movej(", "movel("}},
      {"fanuc", {"J P[", "L P["}}, {"val3", {"movej(", "movel("}},  {"gcode", {"G0 X", "G1 X"}}};
  for (const auto& [format, kinds] : moves) {
    const Program p = write_program(two_paths(), format, o);
    EXPECT_EQ(count_of(p.files[0].text, kinds.first), 2u) << format;
    EXPECT_EQ(count_of(p.files[0].text, kinds.second), 12u) << format;
    if (format == "krl" || format == "urscript" || format == "gcode") {
      const std::vector<Parsed> parsed = parse(format, p.files[0].text);
      ASSERT_EQ(parsed.size(), planned.size()) << format;
      for (std::size_t i = 0; i < planned.size(); ++i) {
        EXPECT_LT((parsed[i].position - planned[i].position_mm).norm(), 1e-5) << format << " " << i;
      }
    }
  }
}

// A home joint position, reached by a joint move before the first path's approach and after the last retract, in
// joints (deg; URScript rad); refused where there are no robot joints.
TEST(RobotProgram, HomeJointPositionAtTheStartAndTheEnd) {
  ProgramOptions o;
  o.name = "t";
  o.home_deg = {0.0, -90.0, 90.0, 0.0, 45.0, 180.0};
  const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> homes = {
      {"krl", {"PTP {A1 0.000000, A2 -90.000000, A3 90.000000, A4 0.000000, A5 45.000000, A6 180.000000}", "PTP {X"}},
      {"rapid", {"MoveAbsJ jHome\\NoEOffs", "MoveJ p1,"}},
      {"urscript",
       {"movej([0.000000000, -1.570796327, 1.570796327, 0.000000000, 0.785398163, 3.141592654])", "movej(p["}},
      {"fanuc", {"J P[15] 100% FINE ;", "J P[1] 100% FINE ;"}},
      {"val3", {"movej(jHome[0], tTool, mApproach)", "movej(pPath[0]"}}};
  for (const auto& [format, lines] : homes) {
    const std::string text = write_program(two_paths(), format, o).files[0].text;
    EXPECT_EQ(count_of(text, lines.first), 2u) << format;
    EXPECT_LT(text.find(lines.first), text.find(lines.second)) << format;  // home before the first approach
    const std::size_t last_motion = std::max(text.rfind("LIN {"), std::max(text.rfind("MoveL "), text.rfind("movel(")));
    const std::size_t last_fanuc = text.rfind("L P[");
    EXPECT_GT(text.rfind(lines.first), std::max(last_motion == std::string::npos ? 0 : last_motion,
                                                last_fanuc == std::string::npos ? 0 : last_fanuc))
        << format;  // and after the last retract
  }
  EXPECT_NE(write_program(two_paths(), "fanuc", o).files[0].text.find("J1 = 0.000000 deg,\tJ2 = -90.000000 deg"),
            std::string::npos);
  EXPECT_NE(write_program(two_paths(), "val3", o).files[1].text.find("j2=\"-90.000000\""), std::string::npos);
  EXPECT_THROW(write_program(two_paths(), "gcode", o), Error);
  EXPECT_THROW(write_program(two_paths(), "csv", o), Error);
  o.home_deg = {0.0, 0.0, 0.0};
  EXPECT_THROW(write_program(two_paths(), "krl", o), Error);
}

// Blending on the interior points of each path only (3 of 5 a path), at the stated distance; none with 0.
TEST(RobotProgram, BlendOnlyThroughTheInteriorPointsOfAPath) {
  ProgramOptions o;
  o.name = "t";
  o.blend_mm = 2.0;
  EXPECT_EQ(count_of(write_program(two_paths(), "urscript", o).files[0].text, ", r=0.002000)"), 6u);
  EXPECT_EQ(count_of(write_program(two_paths(), "krl", o).files[0].text, "} C_DIS"), 6u);
  EXPECT_EQ(count_of(write_program(two_paths(), "krl", o).files[0].text, "$APO.CDIS = 2.000"), 1u);
  const std::string rapid = write_program(two_paths(), "rapid", o).files[0].text;
  EXPECT_EQ(count_of(rapid, ", zPath, "), 6u);
  EXPECT_EQ(count_of(rapid, "zonedata zPath := [FALSE,2.000,2.000,2.000,0.2000,2.000,0.2000]"), 1u);
  EXPECT_EQ(count_of(write_program(two_paths(), "fanuc", o).files[0].text, "CNT100"), 6u);
  EXPECT_EQ(count_of(write_program(two_paths(), "val3", o).files[0].text, ", mPath)"), 6u);
  o.blend_mm = 0.0;
  EXPECT_EQ(count_of(write_program(two_paths(), "urscript", o).files[0].text, ", r="), 0u);
  EXPECT_EQ(count_of(write_program(two_paths(), "krl", o).files[0].text, "C_DIS"), 0u);
  EXPECT_EQ(count_of(write_program(two_paths(), "rapid", o).files[0].text, "zPath"), 0u);
  EXPECT_EQ(count_of(write_program(two_paths(), "fanuc", o).files[0].text, "CNT"), 0u);
  o.blend_mm = -1.0;
  EXPECT_THROW(write_program(two_paths(), "urscript", o), Error);
}

}  // namespace
}  // namespace conform
