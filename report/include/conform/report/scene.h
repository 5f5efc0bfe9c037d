#pragma once
// The 3D view of a report (docs/report.md): named objects (points, a triangle mesh, polylines, arrows), each a layer
// the reader can switch on and off, and an optional colour bar. Coordinates are millimetres in the job's frame, kept
// in double here; the page gets them as float32 relative to the scene's origin (the mean of every position, in
// double), so that shop-frame coordinates 100 m out render without float jitter. The origin is stated on the page.
//
// Big inputs are thinned for the page, deterministically, to the Limits below (points by an even stride, meshes by
// vertex clustering on a grid); each thinning is stated on the page (notes()).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"

namespace conform::html {

using Rgb = std::array<std::uint8_t, 3>;

// A few colours that read well on the view's light background.
inline constexpr Rgb kGrey = {150, 150, 150};
inline constexpr Rgb kDarkGrey = {70, 70, 70};
inline constexpr Rgb kBlue = {31, 119, 180};
inline constexpr Rgb kOrange = {255, 127, 14};
inline constexpr Rgb kGreen = {44, 160, 44};
inline constexpr Rgb kRed = {214, 39, 40};
inline constexpr Rgb kPurple = {148, 103, 189};

enum class ObjectKind { kPoints, kMesh, kPolyline, kArrows };

struct SceneObject {
  std::string name;  // the layer's label (unique in a scene)
  ObjectKind kind = ObjectKind::kPoints;
  bool visible = true;  // shown when the page opens
  std::vector<Eigen::Vector3d> positions;  // points; mesh vertices; polyline points; arrow origins (mm)
  std::vector<Eigen::Vector3d> directions;  // arrows: unit directions, one per origin
  std::vector<std::array<std::uint32_t, 3>> triangles;  // mesh
  std::vector<Rgb> colours;  // empty (one colour) or one per position
  Rgb colour = kGrey;
  double size_px = 2.0;      // points: on-screen size in pixels
  double opacity = 1.0;      // mesh: (0, 1]
  double length_mm = 1.0;    // arrows: drawn length
  bool closed = false;       // polyline: the last point joins the first
  bool pieces = false;       // polyline: positions are pairs, each a segment (several lines in one layer)
  // Optional: one value per position (e.g. the signed deviation), shown with the coordinates when the reader clicks
  // the point; `value_label` names it with its unit ("deviation (mm)").
  std::vector<double> values;
  std::string value_label;
  std::size_t original_count = 0;  // points or triangles before thinning
};

// The colour scale of a coloured layer, drawn beside the view: `stops` sampled from the map between min and max,
// an optional band (e.g. the tolerance +-t) marked on it.
struct ColourBar {
  std::string title;  // "deviation (mm)"
  std::string map;    // the colour map's name, as stated on the page
  double min = 0.0;
  double max = 1.0;
  std::vector<std::pair<double, Rgb>> stops;  // ascending values in [min, max]
  std::optional<std::pair<double, double>> band;
};

// `samples` (>= 2) evenly spaced stops of `colour` over [min, max] (min < max).
template <typename ColourFn>
ColourBar make_colour_bar(std::string title, std::string map, double min, double max, ColourFn colour,
                          int samples = 65) {
  ColourBar bar{std::move(title), std::move(map), min, max, {}, std::nullopt};
  for (int i = 0; i < samples; ++i) {
    const double v = min + (max - min) * i / (samples - 1);
    bar.stops.emplace_back(v, colour(v));
  }
  return bar;
}

// A labelled marker the view keeps beside a point (e.g. "1: +1.482 mm" at the worst point), with a leader line.
struct Callout {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // mm, the job's frame
  std::string label;
};

class Scene {
 public:
  // Totals over the whole scene; an object over its share (its size over the total of its kind) is thinned.
  // About 15 bytes a point and 12 a triangle (plus its vertices) before base64: the defaults keep a page < ~20 MB.
  struct Limits {
    std::size_t max_points = 300000;       // points objects together
    std::size_t max_triangles = 400000;    // meshes together
    std::size_t max_line_points = 200000;  // polylines together
    std::size_t max_arrows = 20000;        // arrows together
  };

  Scene() = default;
  explicit Scene(Limits limits) : limits_(limits) {}

  // Each returns the object added, to adjust (e.g. visible = false; the reference holds until the next add_*).
  // Throws std::invalid_argument when a per-item array does not match the positions, or the name is already used.
  SceneObject& add_points(const std::string& name, const std::vector<Eigen::Vector3d>& positions, Rgb colour,
                          double size_px = 2.0);
  SceneObject& add_points(const std::string& name, const std::vector<Eigen::Vector3d>& positions,
                          const std::vector<Rgb>& colours, double size_px = 2.0);
  // A mesh, lit, one colour or per-vertex colours (empty: `colour`), opacity in (0, 1].
  SceneObject& add_mesh(const std::string& name, const std::vector<Eigen::Vector3d>& vertices,
                        const std::vector<Face>& triangles, Rgb colour, double opacity = 1.0,
                        const std::vector<Rgb>& vertex_colours = {});
  SceneObject& add_mesh(const std::string& name, const Mesh& mesh, Rgb colour, double opacity = 1.0);
  SceneObject& add_polyline(const std::string& name, const std::vector<Eigen::Vector3d>& points, Rgb colour,
                            bool closed = false);
  // Several open lines as one layer (e.g. the paths of one weld layer): stored as segment pairs (pieces).
  SceneObject& add_polylines(const std::string& name, const std::vector<std::vector<Eigen::Vector3d>>& lines,
                             Rgb colour);
  // Glyphs: a line of `length_mm` from each origin along its direction (normalised here; zero ones are skipped),
  // with a dot at the origin. For tool normals, cut and weld directions.
  SceneObject& add_arrows(const std::string& name, const std::vector<Eigen::Vector3d>& origins,
                          const std::vector<Eigen::Vector3d>& directions, double length_mm, Rgb colour);

  void set_colour_bar(ColourBar bar) { colour_bar_ = std::move(bar); }
  // Callouts are drawn over the view (a layer of their own, "callouts"), in the order added.
  void add_callout(const Eigen::Vector3d& position, std::string label) {
    callouts_.push_back({position, std::move(label)});
  }
  const std::vector<Callout>& callouts() const { return callouts_; }
  const std::optional<ColourBar>& colour_bar() const { return colour_bar_; }

  const std::vector<SceneObject>& objects() const { return objects_; }
  const Limits& limits() const { return limits_; }
  bool empty() const { return objects_.empty(); }

  // The mean of every position of every object (mm, double); zero for an empty scene.
  Eigen::Vector3d origin() const;
  // The objects as drawn on the page: each thinned to its share of the limits (same scene, same result).
  std::vector<SceneObject> thinned() const;
  // One sentence per thinned object: "scan: 1200000 points, 300000 shown (every 4th, ...)".
  std::vector<std::string> notes() const { return notes(thinned()); }
  // The same, from thinned() computed already.
  std::vector<std::string> notes(const std::vector<SceneObject>& thinned) const;

 private:
  SceneObject& add(SceneObject object);

  Limits limits_;
  std::vector<SceneObject> objects_;
  std::optional<ColourBar> colour_bar_;
  std::vector<Callout> callouts_;
};

// Mesh thinning by vertex clustering: vertices merged per cell of a cubic grid (the first vertex of a cell stands
// for it, so the result is a subset of the input's vertices) and the triangles that collapse dropped; the cell grows
// by 1.25 until at most `max_triangles` remain. Returns the object unchanged when it is within the limit.
SceneObject thin_mesh(const SceneObject& mesh, std::size_t max_triangles);
// Every k-th item (k = ceil(n / max_items)), from the first; per-item arrays follow.
SceneObject thin_by_stride(const SceneObject& object, std::size_t max_items);

}  // namespace conform::html
