#include "conform/pipelines/inspect/inspect_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "conform/core/constants.h"
#include "conform/pipelines/common/deviation_view.h"
#include "conform/pipelines/inspect/inspect_json.h"

namespace conform {
namespace {

html::Verdict verdict_of(const InspectResult& r) {
  if (!r.ok) return {html::Level::kFail, r.termination};
  char text[256];
  std::snprintf(text, sizeof text, "%zu of %zu points on %zu faces", r.assigned, r.scan_points, r.faces.size());
  if (r.verdict.empty()) return {html::Level::kCheck, std::string("no tolerances given: ") + text};
  if (r.verdict == "pass") return {html::Level::kOk, std::string("every toleranced face passes: ") + text};
  if (r.verdict == "incomplete") {
    return {html::Level::kCheck, std::string("no toleranced face fails, but one was not measured: ") + text};
  }
  return {html::Level::kFail, std::string("a toleranced face FAILS: ") + text};
}

std::string feature_text(const FaceInspection& f) {
  char text[200];
  if (f.fitted && f.nominal.type == CadSurfaceType::kCylinder) {
    std::snprintf(text, sizeof text, "radius %.4f (nominal %.4f) mm, axis offset %.4f mm, %.3f deg", f.radius_mm,
                  f.nominal.radius_mm, f.axis_offset_mm, f.axis_angle_deg);
    return text;
  }
  if (f.fitted && f.nominal.type == CadSurfaceType::kSphere) {
    std::snprintf(text, sizeof text, "radius %.4f (nominal %.4f) mm, centre offset %.4f mm", f.radius_mm,
                  f.nominal.radius_mm, f.centre_offset_mm);
    return text;
  }
  if (f.fitted && f.nominal.type == CadSurfaceType::kCone) {
    std::snprintf(text, sizeof text, "half-angle %.4f (nominal %.4f) deg, axis offset %.4f mm", f.half_angle_deg,
                  degrees(f.nominal.half_angle_rad), f.axis_offset_mm);
    return text;
  }
  if (f.fitted && f.nominal.type == CadSurfaceType::kTorus) {
    std::snprintf(text, sizeof text, "radii %.4f / %.4f (nominal %.4f / %.4f) mm, centre offset %.4f mm", f.radius_mm,
                  f.minor_radius_mm, f.nominal.radius_mm, f.nominal.minor_radius_mm, f.centre_offset_mm);
    return text;
  }
  if (f.fitted && f.nominal.type == CadSurfaceType::kPlane) {
    std::snprintf(text, sizeof text, "normal %.4f deg from nominal, offset %.4f mm", f.angle_to_nominal_deg,
                  f.plane_offset_mm);
    return text;
  }
  return f.fit_note;
}

// With datums, the figures at the best fit beside the datum frame's (docs/inspect.md, Output).
bool best_fit_beside(const InspectResult& r) { return r.best_fit.computed && r.best_fit.converged; }

// A face's mean, std, min, max and form cells, tied to the JSON object at `at`.
void add_deviation_cells(const FaceInspection& f, const std::string& at, std::vector<html::Cell>& row) {
  if (f.points > 0) {
    row.push_back(html::number(f.deviation.mean_mm, 4, at + "mean_mm"));
    row.push_back(html::number(f.deviation.std_mm, 4, at + "std_mm"));
    row.push_back(html::number(f.deviation.min_mm, 4, at + "min_mm"));
    row.push_back(html::number(f.deviation.max_mm, 4, at + "max_mm"));
  } else {
    row.insert(row.end(), 4, html::Cell("-"));
  }
  row.push_back(f.form_measured ? html::number(f.form.width_mm, 4, at + "form_mm") : html::Cell("-"));
}

// A face's or a feature's verdict in its table: "-" when not toleranced.
template <typename Verdict>
html::Cell verdict_cell(const std::optional<Verdict>& verdict) {
  return !verdict ? "-" : !verdict->measured ? "not measured" : verdict->pass ? "pass" : "FAIL";
}

html::Table faces_table(const InspectResult& r) {
  const bool beside = best_fit_beside(r);
  html::Table t;
  t.title = "Faces";
  t.header = {"face", "type", "points", "mean mm", "std mm", "min mm", "max mm", "form mm"};
  if (beside) {
    t.header.insert(t.header.end(), {"best-fit mean mm", "best-fit std mm", "best-fit min mm", "best-fit max mm",
                                     "best-fit form mm"});
  }
  t.header.insert(t.header.end(), {"feature", "verdict"});
  for (std::size_t k = 0; k < r.faces.size(); ++k) {
    const FaceInspection& f = r.faces[k];
    const std::string at = "/faces/" + std::to_string(k) + "/";
    std::vector<html::Cell> row = {html::count(f.id, at + "id"), std::string(to_string(f.nominal.type)),
                                   html::count(f.points, at + "points")};
    add_deviation_cells(f, at, row);
    if (beside) add_deviation_cells(r.best_fit.faces[k], at + "best_fit/", row);
    row.push_back(feature_text(f));
    row.push_back(verdict_cell(f.verdict));
    t.rows.push_back(std::move(row));
  }
  return t;
}

html::Table features_table(const InspectResult& r) {
  const bool beside = best_fit_beside(r);
  html::Table t;
  t.title = "Holes and bosses";
  t.header = {"feature", "kind", "faces", "points", "diameter mm", "nominal mm", "position mm", "perpendicularity mm",
              "cylindricity mm"};
  if (beside) t.header.insert(t.header.end(), {"best-fit diameter mm", "best-fit position mm"});
  t.header.push_back("verdict");
  for (std::size_t k = 0; k < r.features.size(); ++k) {
    const FeatureInspection& feature = r.features[k];
    const FaceInspection& f = feature.measured;
    const std::string at = "/features/" + std::to_string(k) + "/";
    std::string faces;
    for (const std::size_t id : feature.faces) faces += (faces.empty() ? "" : " ") + std::to_string(id);
    std::vector<html::Cell> row = {html::count(feature.id, at + "id"), f.nominal.sense < 0 ? "hole" : "boss", faces,
                                   html::count(f.points, at + "points")};
    if (f.fitted) {
      row.push_back(html::number(2.0 * f.radius_mm, 4, at + "diameter_mm"));
      row.push_back(html::number(2.0 * f.nominal.radius_mm, 4, at + "nominal_diameter_mm"));
      row.push_back(html::number(f.position_mm, 4, at + "position_mm"));
      row.push_back(std::isfinite(f.perpendicularity_mm) ? html::number(f.perpendicularity_mm, 4,
                                                                        at + "perpendicularity_mm")
                                                         : html::Cell("-"));
      row.push_back(html::number(f.form.width_mm, 4, at + "form_mm"));
    } else {
      row.insert(row.end(), 5, html::Cell(f.fit_note.empty() ? "-" : f.fit_note));
    }
    if (beside) {
      const FaceInspection& b = r.best_fit.features[k].measured;
      if (b.fitted) {
        row.push_back(html::number(2.0 * b.radius_mm, 4, at + "best_fit/diameter_mm"));
        row.push_back(html::number(b.position_mm, 4, at + "best_fit/position_mm"));
      } else {
        row.insert(row.end(), 2, html::Cell("-"));
      }
    }
    row.push_back(verdict_cell(feature.verdict));
    t.rows.push_back(std::move(row));
  }
  return t;
}

// One layer per measured or toleranced face (its triangles, so that it can be shown alone): red when it fails its
// tolerances (shown when the page opens), green when it passes, grey otherwise (hidden). At most kMaxFaceLayers.
constexpr std::size_t kMaxFaceLayers = 200;

void add_face_layers(const InspectResult& r, html::Page& page) {
  if (r.reference_triangle_face.size() != r.reference.faces.size()) return;
  std::vector<std::vector<std::size_t>> triangles(r.faces.size());
  for (std::size_t t = 0; t < r.reference.faces.size(); ++t) {
    triangles[static_cast<std::size_t>(r.reference_triangle_face[t])].push_back(t);
  }
  std::size_t layers = 0;
  for (std::size_t k = 0; k < r.faces.size() && layers < kMaxFaceLayers; ++k) {
    const FaceInspection& f = r.faces[k];
    if ((f.points == 0 && !f.verdict) || triangles[k].empty()) continue;
    std::vector<Eigen::Vector3d> vertices;
    std::vector<Face> faces;
    for (const std::size_t t : triangles[k]) {
      const Face& tri = r.reference.faces[t];
      const auto base = static_cast<std::int32_t>(vertices.size());
      for (const std::int32_t v : tri) vertices.push_back(r.reference.vertices[static_cast<std::size_t>(v)]);
      faces.push_back({base, base + 1, base + 2});
    }
    const bool judged = f.verdict && f.verdict->measured;
    const bool fails = judged && !f.verdict->pass;
    const std::string state = !f.verdict ? "" : !judged ? ": not measured" : fails ? ": FAIL" : ": pass";
    html::SceneObject& layer =
        page.scene.add_mesh("face " + std::to_string(f.id) + " " + to_string(f.nominal.type) + state, vertices, faces,
                            fails ? html::kRed : judged ? html::kGreen : html::kGrey, 0.6);
    layer.visible = fails;
    ++layers;
  }
}

}  // namespace

html::Page inspect_report(const InspectOptions& options, const InspectResult& r, const nlohmann::json& json,
                          const std::string& date) {
  html::Page page;
  page.job = "inspect";
  page.title = "conform inspect: " + std::filesystem::path(options.scan_path).filename().string() + " against " +
               std::filesystem::path(options.reference_path).filename().string();
  page.inputs.push_back({options.scan_path, std::to_string(r.scan_points) + " points"});
  page.inputs.push_back({options.reference_path, std::to_string(r.faces.size()) + " faces"});
  if (!options.transform_path.empty()) page.inputs.push_back({options.transform_path, "T_ref_scan"});
  if (!options.tolerances_path.empty()) page.inputs.push_back({options.tolerances_path, "tolerances"});
  page.options = {{"units", json.value("units", "mm")},
                  {"alignment", r.alignment},
                  {"max_distance_mm", r.max_distance_mm},
                  {"max_normal_angle_deg", json.value("max_normal_angle_deg", 30.0)},
                  {"form_trim", options.form_trim}};
  if (!options.datum_faces.empty()) page.options["datums"] = options.datum_faces;
  page.date = date;
  page.verdict = verdict_of(r);
  page.warnings = r.warnings;
  page.result = json;
  if (!r.scan_ref.vertices.empty()) {
    html::DeviationView view;
    view.reference_name = "CAD";
    view.tie_to_json = false;  // the statistics of all assigned points; the JSON has them per face
    const DeviationStatistics all = deviation_statistics(r.deviation_mm);
    html::add_deviation_view(page, r.scan_ref.vertices, r.deviation_mm, all, r.reference, view);
    page.sections.back().paragraphs.insert(
        page.sections.back().paragraphs.begin(),
        "Signed distance of every scan point assigned to a CAD face from that face, + outside: to the exact surface "
        "of planes, cylinders, cones, spheres and tori, to the tessellation for other faces. Points on no face are "
        "grey.");
  }
  add_face_layers(r, page);
  html::Section faces;
  faces.title = "Faces";
  faces.paragraphs.push_back(
      "Form: the width of the zone about the least-squares plane or cylinder (else the nominal surface) holding all "
      "but the trimmed share of the residuals (docs/inspect.md). In the view each measured face is a layer of its own "
      "(red: fails its tolerances, shown; green: passes; grey: not toleranced).");
  if (best_fit_beside(r)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "With datums every figure is in the datum frame; the best-fit columns give the same figures at the "
                  "best fit of the whole scan (%s), which is %.4f mm (the largest move of a scan point) and %.4f deg "
                  "from the datum frame (a turn about a part's symmetry axis changes no figure).",
                  best_fit_pose_name(r.alignment),
                  r.best_fit.displacement_mm, r.best_fit.angle_deg);
    faces.paragraphs.push_back(text);
  }
  faces.tables.push_back(faces_table(r));
  if (!r.features.empty()) faces.tables.push_back(features_table(r));
  page.sections.push_back(std::move(faces));
  return page;
}

}  // namespace conform
