#pragma once
// How Subdivision-ICP cuts a contour (Béarée, Dieulot & Rabaté 2010, section 3): the radius of the osculating circle
// at every point, subdivision points where the contour bends sharply (radius below a threshold: a corner), and more
// subdivision points every epsilon of arc length in between, so that every segment is nearly straight and short
// enough for one rigid transform to follow the part's deformation. Neighbouring segments overlap, so that their
// transforms can be blended (compensation/sicp_blend.h).
//
// Positions along the contour are arc lengths s in mm from its first point; on a closed contour they wrap at its
// length L (the closing edge included).

#include <cstddef>
#include <string>
#include <vector>

#include "conform/core/polyline.h"

namespace conform {

struct ContourSegmentationOptions {
  double segment_length_mm = 40.0;  // epsilon: the longest segment (its core, overlaps excluded), in [1, 1e5] mm
  // Each junction's overlap, as a share of the shorter of the two segments that meet there, in (0, 1). The paper
  // uses 20-40%; the overlap is centred on the junction.
  double overlap = 0.3;
  double curvature_radius_mm = 15.0;  // a point whose osculating radius is below this is a corner candidate; 0: none
  double curvature_window_mm = 2.0;   // the osculating circle passes through the points this far before and after
  // The most segments a contour may be cut into, checked before anything is allocated for them (each segment costs an
  // ICP): a contour point far off (a unit error) or a tiny segment length is refused, naming this limit. >= 1.
  std::size_t max_segments = 2000;
  bool IsValid(std::string* error) const;
};

struct ContourSegment {
  double start_mm = 0.0;           // where the core starts (arc length, in [0, L) on a closed contour)
  double length_mm = 0.0;          // the core's length; the cores tile the contour without gaps
  double overlap_before_mm = 0.0;  // half the overlap with the previous segment: the segment reaches this far back
  double overlap_after_mm = 0.0;   // half the overlap with the next one
  bool starts_at_corner = false;
  bool ends_at_corner = false;
};

struct ContourSegmentation {
  bool closed = false;
  double length_mm = 0.0;                // L
  std::vector<double> arc_length_mm;     // per contour point
  std::vector<double> radius_mm;         // osculating radius per point (infinity on a straight stretch)
  std::vector<int> corners;              // point indices of the subdivision points at sharp bends, ascending
  std::vector<ContourSegment> segments;  // in contour order

  // Offset of s from `from` along the contour: s - from, wrapped into [0, L) on a closed contour.
  double ahead(double from, double s) const;
  // Does segment k reach s (its core plus its overlaps)?
  bool reaches(std::size_t k, double s) const;
  // The segment whose core holds s (binary search; beyond an open contour's ends, the end segment). Only it and its
  // two neighbours can reach s: an overlap is shorter than either segment it joins.
  std::size_t core_at(double s) const;
};

// Arc length of every point from the first (mm).
std::vector<double> arc_lengths(const Polyline& contour);

// Radius of the circle through the points window_mm before and after each point and the point itself (their
// circumradius |a||b||c| / (4 area), Eq. (5) of the paper); infinity where they are collinear. At the ends of an
// open contour the window is clamped to the ends.
std::vector<double> osculating_radii(const Polyline& contour, double window_mm);

// Throws conform::Error for invalid options, fewer than 3 points, a non-finite point, a contour of zero length or one
// that would need more than max_segments segments.
ContourSegmentation segment_contour(const Polyline& contour, const ContourSegmentationOptions& options);

}  // namespace conform
