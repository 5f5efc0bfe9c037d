#pragma once
// Designed features of a profile in its straight, flat coordinates (Tx across the web from the edge, Ty along the
// edge from the origin; mm), and their sampling into points to map: a feature's outline is cut as a polyline, so it
// is sampled densely enough that, once mapped onto the deformed profile, no chord strays further than a tolerance
// from the mapped outline (Chen et al. map points; outlines are this file's concern).
//
//   point     one vertex                               -> one point
//   circle    centre vertex + radius                   -> closed outline (first point repeated last) + centre
//   slot      two vertices (centre-line ends) + radius -> closed stadium outline + centre (the middle of the ends)
//   polyline  vertices in order, open (marking line)   -> the line through the vertices
//   polygon   vertices in order, closed (cut-out)      -> closed outline (first vertex repeated last)

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

enum class ProfileFeatureType { kPoint, kCircle, kSlot, kPolyline, kPolygon };

const char* to_string(ProfileFeatureType type);
// "point", "circle", "slot", "polyline" or "polygon"; false for anything else.
bool parse_profile_feature_type(const std::string& text, ProfileFeatureType* type);

// No ship profile is longer than this: a designed coordinate beyond it is a broken file, not a design (mm).
constexpr double kProfileFeatureLimitMm = 1e6;

struct ProfileFeature {
  std::string id;
  ProfileFeatureType type = ProfileFeatureType::kPoint;
  std::vector<Eigen::Vector2d> vertices;  // (Tx, Ty), mm
  double radius_mm = 0.0;                 // circle and slot
  std::string where;                      // where it was read ("features.csv:4"), for messages

  // Throws conform::Error (naming id and where) for a wrong vertex count, a radius that is not positive where one is
  // needed, a coordinate or radius that is not finite or absurd (beyond kProfileFeatureLimitMm), or a slot whose ends
  // coincide.
  void validate() const;
  // The designed centre for circle and slot (the middle of the slot's ends); false for the others.
  bool centre(Eigen::Vector2d* centre) const;
  // The smallest and largest Ty the feature reaches (outline included).
  void ty_range(double* lo, double* hi) const;
  // The smallest and largest Tx the feature reaches (outline included).
  void tx_range(double* lo, double* hi) const;
};

// Maps a designed (Tx, Ty) to 3D.
using ProfilePointMap = std::function<Eigen::Vector3d(const Eigen::Vector2d& designed)>;

struct ProfileSampleOptions {
  double chord_tolerance_mm = 0.05;  // largest distance of a mapped chord's middle from the mapped outline, mm (> 0)
  int max_depth = 16;                // bisections of one initial piece at most

  bool IsValid(std::string* error) const;
};

// The designed points of a feature's outline (closed outlines end on their first point), chosen so that the mapped
// polyline meets the chord tolerance: arcs start at the angle step that meets it on the flat profile, every piece is
// bisected while its mapped middle lies further than the tolerance from its mapped chord. Vertices are always kept.
std::vector<Eigen::Vector2d> sample_profile_feature(const ProfileFeature& feature, const ProfilePointMap& map,
                                                    const ProfileSampleOptions& options);

}  // namespace conform
