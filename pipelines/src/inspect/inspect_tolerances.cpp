#include "inspect/inspect_tolerances.h"

#include <algorithm>
#include <optional>

#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "inspect/inspect_feature_groups.h"

namespace conform::detail {

namespace {

constexpr const char* kLimitColumns[] = {"lower_mm",          "upper_mm",          "form_mm",
                                         "diameter_lower_mm", "diameter_upper_mm", "position_mm"};

// The cell of a column the file may not have: empty (not toleranced) when it has not.
std::optional<double> optional_number(const CsvTable& table, std::size_t row, const char* name) {
  if (!table.has_column(name)) return std::nullopt;
  const std::size_t column = table.column(name);
  if (table.text(row, column).empty()) return std::nullopt;
  return table.number(row, column);
}

std::string text_of(const CsvTable& table, std::size_t row, const char* name) {
  return table.text(row, table.column(name));
}

// Per face (0-based), the index of its feature (features.size() for a face on none).
std::vector<std::size_t> feature_of_faces(const std::vector<CadFace>& faces) {
  const std::vector<std::vector<std::size_t>> features = cylinder_features(faces);
  std::vector<std::size_t> out(faces.size(), features.size());
  for (std::size_t k = 0; k < features.size(); ++k) {
    for (const std::size_t f : features[k]) out[f] = k;
  }
  return out;
}

}  // namespace

Tolerances read_tolerances(const std::string& path, const std::vector<CadFace>& faces) {
  const CsvTable table = read_csv(path, {"face"});
  bool any_limit_column = false;
  for (const char* name : kLimitColumns) any_limit_column = any_limit_column || table.has_column(name);
  if (!any_limit_column) {
    throw Error(path + ": no limit column (lower_mm, upper_mm, form_mm, diameter_lower_mm, diameter_upper_mm, "
                       "position_mm)");
  }
  const std::size_t face = table.column("face");
  const std::size_t face_count = faces.size();
  const std::vector<std::size_t> feature_of = feature_of_faces(faces);
  Tolerances out;
  std::vector<bool> seen(face_count + 1, false);
  std::vector<std::size_t> feature_row(face_count + 1, 0);  // per feature index: the line that limits it
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const std::string where = path + ":" + std::to_string(table.line_numbers[r]) + ": ";
    const std::int64_t id = table.integer(r, face);
    if (id < 1 || static_cast<std::uint64_t>(id) > face_count) {
      throw Error(where + "face " + std::to_string(id) + " is not one of the CAD's faces 1.." +
                  std::to_string(face_count));
    }
    const auto f = static_cast<std::size_t>(id);
    if (seen[f]) throw Error(where + "face " + std::to_string(id) + " is given twice");
    seen[f] = true;
    FaceTolerance t;
    t.face_id = f;
    t.lower_mm = optional_number(table, r, "lower_mm");
    t.upper_mm = optional_number(table, r, "upper_mm");
    t.form_mm = optional_number(table, r, "form_mm");
    if (t.lower_mm && t.upper_mm && *t.lower_mm > *t.upper_mm) {
      throw Error(where + "lower_mm " + text_of(table, r, "lower_mm") + " is above upper_mm " +
                  text_of(table, r, "upper_mm"));
    }
    if (t.form_mm && !(*t.form_mm > 0.0)) {
      throw Error(where + "form_mm must be > 0, not " + text_of(table, r, "form_mm"));
    }
    FeatureTolerance ft;
    ft.face_id = f;
    ft.diameter_lower_mm = optional_number(table, r, "diameter_lower_mm");
    ft.diameter_upper_mm = optional_number(table, r, "diameter_upper_mm");
    ft.position_mm = optional_number(table, r, "position_mm");
    const bool face_limits = t.lower_mm || t.upper_mm || t.form_mm;
    const bool feature_limits = ft.diameter_lower_mm || ft.diameter_upper_mm || ft.position_mm;
    if (!face_limits && !feature_limits) throw Error(where + "face " + std::to_string(id) + " has no limit");
    if (face_limits) out.faces.push_back(t);
    if (!feature_limits) continue;
    const std::size_t k = feature_of[f - 1];
    if (faces[f - 1].type != CadSurfaceType::kCylinder) {
      throw Error(where + "face " + std::to_string(id) + " is a " + to_string(faces[f - 1].type) +
                  ": diameter and position limits are for holes and bosses (cylinder faces)");
    }
    if (feature_row[k] != 0) {
      throw Error(where + "face " + std::to_string(id) + " is on the same hole or boss as the face of line " +
                  std::to_string(feature_row[k]) + ": its size and position are limited twice");
    }
    feature_row[k] = table.line_numbers[r];
    if (ft.diameter_lower_mm && ft.diameter_upper_mm && *ft.diameter_lower_mm > *ft.diameter_upper_mm) {
      throw Error(where + "diameter_lower_mm " + text_of(table, r, "diameter_lower_mm") +
                  " is above diameter_upper_mm " + text_of(table, r, "diameter_upper_mm"));
    }
    if (ft.position_mm && !(*ft.position_mm > 0.0)) {
      throw Error(where + "position_mm must be > 0, not " + text_of(table, r, "position_mm"));
    }
    out.features.push_back(ft);
  }
  if (table.rows() == 0) throw Error(path + ": no face is toleranced (no rows after the header)");
  return out;
}

void judge_tolerances(const Tolerances& tolerances, InspectResult& result) {
  bool failed = false, unmeasured = false;
  for (const FaceTolerance& t : tolerances.faces) {
    FaceInspection& face = result.faces[t.face_id - 1];
    FaceVerdict v;
    v.tolerance = t;
    if (face.points == 0 || (t.form_mm && !face.form_measured)) {
      v.measured = false;
      unmeasured = true;
    } else {
      v.measured = true;
      v.profile_pass = (!t.lower_mm || face.deviation.min_mm >= *t.lower_mm) &&
                       (!t.upper_mm || face.deviation.max_mm <= *t.upper_mm);
      v.form_pass = !t.form_mm || face.form.width_mm <= *t.form_mm;
      v.pass = v.profile_pass && v.form_pass;
      failed = failed || !v.pass;
    }
    face.verdict = v;
  }
  for (const FeatureTolerance& t : tolerances.features) {
    for (FeatureInspection& feature : result.features) {
      if (std::find(feature.faces.begin(), feature.faces.end(), t.face_id) == feature.faces.end()) continue;
      const FaceInspection& m = feature.measured;
      FeatureVerdict v;
      v.tolerance = t;
      v.measured = m.fitted;
      if (v.measured) {
        const double diameter = 2.0 * m.radius_mm;
        v.size_pass = (!t.diameter_lower_mm || diameter >= *t.diameter_lower_mm) &&
                      (!t.diameter_upper_mm || diameter <= *t.diameter_upper_mm);
        v.position_pass = !t.position_mm || m.position_mm <= *t.position_mm;
        v.pass = v.size_pass && v.position_pass;
        failed = failed || !v.pass;
      } else {
        unmeasured = true;
      }
      feature.verdict = v;
    }
  }
  result.verdict = failed ? "fail" : unmeasured ? "incomplete" : "pass";
}

}  // namespace conform::detail
