#include "align/align_inputs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "conform/core/error.h"
#include "conform/core/input_file.h"
#include "conform/core/geometry.h"
#include "conform/core/io.h"
#include "conform/core/units.h"
#include "common/cad_inputs.h"

namespace conform::detail {

namespace {

// Hash of a point's coordinates, for merging duplicates: equal values (0 and -0 too) hash alike.
std::size_t point_hash(const Eigen::Vector3d& p) {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (int k = 0; k < 3; ++k) {
    const double v = p[k] == 0.0 ? 0.0 : p[k];
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof(bits));
    h = (h ^ bits) * 0xff51afd7ed558ccdULL;
    h ^= h >> 32;
  }
  return static_cast<std::size_t>(h);
}

// The named unit mix-up closest to a size ratio (>= 1), or "" when none is near.
std::string likely_units(double ratio) {
  const std::pair<double, const char*> known[] = {{1000.0, "metres against millimetres"},
                                                  {25.4, "inches against millimetres"},
                                                  {10.0, "centimetres against millimetres"},
                                                  {100.0, "metres against centimetres"}};
  for (const auto& [factor, words] : known) {
    if (std::abs(std::log(ratio / factor)) < std::log(1.5)) return words;
  }
  return "";
}

// Numbers on one line of the pairs file: spaces, tabs or commas between them; '#' ends the line.
bool parse_numbers(std::string line, std::vector<double>& out) {
  out.clear();
  line = line.substr(0, line.find('#'));
  std::replace(line.begin(), line.end(), ',', ' ');
  const char* p = line.c_str();
  while (true) {
    while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
    if (*p == '\0') return true;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v) || (*end != '\0' && *end != ' ' && *end != '\t' && *end != '\r')) return false;
    out.push_back(v);
    p = end;
  }
}

}  // namespace

Mesh read_for_alignment(const std::string& path, const char* what, double mm_per_unit,
                        std::vector<std::string>& warnings, const CadReadOptions& cad,
                        std::vector<CadReport>* cad_reports) {
  const ReadOptions read = read_options(NonFinitePolicy::kDrop, cad);
  ReadReport report;
  Mesh mesh = read_geometry(path, read, &report);
  for (const std::string& w : report.warnings) warnings.push_back(w);  // they name the file
  if (mesh.vertices.empty()) {
    throw Error(path + ": the " + std::string(what) + " holds no points" +
                (report.non_finite_points > 0 ? " (all had NaN or infinite coordinates)" : ""));
  }
  if (cad_reports != nullptr) keep_cad_report(report, *cad_reports);
  if (mm_per_unit != 1.0 && !cad_keeps_its_units(report, mm_per_unit, warnings)) scale_in_place(mesh, mm_per_unit);
  return mesh;
}

std::vector<Eigen::Vector3d> unique_points(const std::vector<Eigen::Vector3d>& points, std::size_t* merged) {
  // An open-addressing table of first occurrences (linear probing, at most half full): one pass and one random
  // access a point, where std::unordered_set allocated a node for each (4 % of the 100k-point align's time).
  std::size_t capacity = 16;
  while (capacity < 2 * points.size()) capacity *= 2;
  constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  if (points.size() >= kEmpty) throw Error("more than 4 billion points: too many to merge duplicates");
  std::vector<std::uint32_t> table(capacity, kEmpty);
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    for (std::size_t slot = point_hash(p) & (capacity - 1);; slot = (slot + 1) & (capacity - 1)) {
      if (table[slot] == kEmpty) {
        table[slot] = static_cast<std::uint32_t>(out.size());
        out.push_back(p);
        break;
      }
      if (out[table[slot]] == p) break;  // == on doubles: -0 equals 0, as point_hash has it
    }
  }
  *merged = points.size() - out.size();
  return out;
}

void check_sizes(const Mesh& scan, const Mesh& reference, const std::string& scan_path,
                 const std::string& reference_path, double max_ratio) {
  const double s = bounding_box(scan).diagonal(), r = bounding_box(reference).diagonal();
  if (!(s > 0.0) || !(r > 0.0)) return;
  const double ratio = std::max(s / r, r / s);
  if (ratio <= max_ratio) return;
  const std::string guess = likely_units(ratio);
  throw Error("the scan (" + scan_path + ", " + std::to_string(s) + " across) and the reference (" + reference_path +
              ", " + std::to_string(r) + " across) differ in size by a factor of " + std::to_string(ratio) +
              (guess.empty() ? "" : ", like " + guess) + ": are they in different units? Give each its own (--scan-units, --reference-units; --units sets "
              "both)");
}

std::vector<PointPair> read_point_pairs(const std::string& path, double scan_mm_per_unit, double reference_mm_per_unit) {
  std::istringstream in(read_input_file(path));
  std::vector<PointPair> pairs;
  std::string line;
  std::vector<double> v;
  constexpr std::size_t kMaxPairs = 1000000;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (!parse_numbers(line, v)) throw Error(where + "not a list of numbers: '" + line + "'");
    if (v.empty()) continue;
    if (v.size() != 6) {
      throw Error(where + std::to_string(v.size()) + " numbers; a pair is 6: scan x y z, then reference x y z");
    }
    if (pairs.size() == kMaxPairs) throw Error(path + ": more than a million point pairs");
    pairs.push_back(
        {Eigen::Vector3d(v[0], v[1], v[2]) * scan_mm_per_unit, Eigen::Vector3d(v[3], v[4], v[5]) * reference_mm_per_unit});
  }
  if (in.bad()) throw Error(path + ": read error");
  if (pairs.size() < 3) {
    throw Error(path + ": holds " + std::to_string(pairs.size()) + " point pairs; at least 3 are needed");
  }
  return pairs;
}

}  // namespace conform::detail
