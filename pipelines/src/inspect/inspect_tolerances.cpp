#include "inspect/inspect_tolerances.h"

#include <optional>

#include "conform/core/csv.h"
#include "conform/core/error.h"

namespace conform::detail {

namespace {

std::optional<double> optional_number(const CsvTable& table, std::size_t row, std::size_t column) {
  if (table.text(row, column).empty()) return std::nullopt;
  return table.number(row, column);
}

}  // namespace

std::vector<FaceTolerance> read_face_tolerances(const std::string& path, std::size_t face_count) {
  const CsvTable table = read_csv(path, {"face", "lower_mm", "upper_mm", "form_mm"});
  const std::size_t face = table.column("face"), lower = table.column("lower_mm"), upper = table.column("upper_mm"),
                    form = table.column("form_mm");
  std::vector<FaceTolerance> out;
  std::vector<bool> seen(face_count + 1, false);
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const std::string where = path + ":" + std::to_string(table.line_numbers[r]) + ": ";
    const std::int64_t id = table.integer(r, face);
    if (id < 1 || static_cast<std::uint64_t>(id) > face_count) {
      throw Error(where + "face " + std::to_string(id) + " is not one of the CAD's faces 1.." +
                  std::to_string(face_count));
    }
    if (seen[static_cast<std::size_t>(id)]) throw Error(where + "face " + std::to_string(id) + " is given twice");
    seen[static_cast<std::size_t>(id)] = true;
    FaceTolerance t;
    t.face_id = static_cast<std::size_t>(id);
    t.lower_mm = optional_number(table, r, lower);
    t.upper_mm = optional_number(table, r, upper);
    t.form_mm = optional_number(table, r, form);
    if (t.lower_mm && t.upper_mm && *t.lower_mm > *t.upper_mm) {
      throw Error(where + "lower_mm " + table.text(r, lower) + " is above upper_mm " + table.text(r, upper));
    }
    if (t.form_mm && !(*t.form_mm > 0.0)) throw Error(where + "form_mm must be > 0, not " + table.text(r, form));
    if (!t.lower_mm && !t.upper_mm && !t.form_mm) throw Error(where + "face " + std::to_string(id) + " has no limit");
    out.push_back(t);
  }
  if (out.empty()) throw Error(path + ": no face is toleranced (no rows after the header)");
  return out;
}

void judge_tolerances(const std::vector<FaceTolerance>& tolerances, InspectResult& result) {
  bool failed = false, unmeasured = false;
  for (const FaceTolerance& t : tolerances) {
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
  result.verdict = failed ? "fail" : unmeasured ? "incomplete" : "pass";
}

}  // namespace conform::detail
