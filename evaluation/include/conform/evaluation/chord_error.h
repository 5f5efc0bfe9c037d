#pragma once
// How far a reference mesh's flat facets may lie from the curved surface they approximate, estimated from the mesh
// alone: a reference exported too coarse for the tolerance (one or two chords a fillet or bend) makes a perfect part
// fail, and nothing else in the numbers says so.
//
//   const ChordErrorEstimate e = estimate_chord_error(reference);
//   const ChordErrorSummary s = summarize_chord_error(reference, e, 0.5 * tolerance_mm);
//   if (s.faces_over > 0) ...  // s.max_mm, s.area_over_mm2 for the warning
//
// A chord of width w across a surface bent by kappa lies kappa w^2 / 8 inside it at its middle (the sagitta). Across an
// edge, the angle phi between the two faces' normals is the bend over about one face width, so kappa w ~ phi and the
// face's sagitta is phi h / 8, h its height over that edge (exact for a cylinder's strips: phi = w / R). Each face
// takes the largest over its edges. Edges over the crease angle are CAD edges (a box's corner, a chamfer), not chords
// of a curve, and faces on a plane of the part (core/planar_regions.h) have no sagitta, however their neighbours bend.

#include <cstddef>
#include <vector>

#include "conform/core/mesh.h"
#include "conform/core/phong_surface.h"

namespace conform {

struct ChordErrorEstimate {
  std::vector<double> sagitta_mm;  // per face, mm; 0 on a plane and for a face without curved neighbours
};

struct ChordErrorSummary {
  double max_mm = 0.0;         // the largest face sagitta
  double bar_mm = 0.0;         // as given
  std::size_t faces_over = 0;  // faces whose sagitta is >= bar_mm
  double area_over_mm2 = 0.0;  // their area
  double area_mm2 = 0.0;       // the whole mesh's area
  double max_over_bar = 0.0;   // max_mm / bar_mm (0 when bar_mm is not > 0)
};

// Throws conform::Error for a face index out of range.
ChordErrorEstimate estimate_chord_error(const Mesh& mesh, double crease_angle_rad = kDefaultCreaseAngleRad);

// The faces whose estimated sagitta reaches bar_mm (> 0), their area and the largest sagitta.
ChordErrorSummary summarize_chord_error(const Mesh& mesh, const ChordErrorEstimate& estimate, double bar_mm);

}  // namespace conform
