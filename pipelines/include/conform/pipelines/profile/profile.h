#pragma once
// `conform profile`: compensate the cutting and marking coordinates of a deformed ship profile (Chen et al., LNG
// profiles; compensation/profile_compensation.h). Reads the measured edge (and optionally the second edge), reads the
// designed features (CSV or JSON), maps every feature onto the deformed profile and writes where to cut, as CSV.
//
//   edge CSV      header x_mm,y_mm,z_mm (other columns ignored), one row per point in measuring order; the first
//                 point is the profile's origin (Ty = 0)
//   features CSV  header id,type,tx_mm,ty_mm[,radius_mm]; rows with the same id, one after the other, are the
//                 vertices of one feature (profile_features.h: point, circle, slot, polyline, polygon)
//   features JSON {"features": [{"id": "H1", "type": "circle", "tx_mm": 100, "ty_mm": 1200, "radius_mm": 50},
//                               {"id": "M1", "type": "polyline", "points_mm": [[185, 600], [185, 11400]]}, ...]}
//   out CSV       id,i,tx_mm,ty_mm,x_mm,y_mm,z_mm,nx,ny,nz,dx,dy,dz: the designed point,
//                 where to cut it, and the tool's frame there (the web's normal, the cut direction along the mapped
//                 outline); the mapped centre of a circle or slot as i = -1, then its outline i = 0, 1, ...

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/compensation/profile_compensation.h"

namespace conform {

struct ProfileJobOptions {
  std::string edge_path;                    // required
  std::string features_path;                // required, .csv or .json (case-insensitive)
  std::string second_edge_path;             // optional: the other edge, for a local web direction (twist)
  ProfileCompensationOptions compensation;  // model, checks, web normal, chord tolerance
  std::string out_path;                     // CSV to write, whole or not at all; empty: write nothing
  bool keep_geometry = false;                 // keep the edge points in the result (for a report)
};

struct ProfileJobResult {
  ProfileCompensationResult compensation;
  std::size_t edge_points = 0;
  std::size_t second_edge_points = 0;
  std::size_t out_rows = 0;  // rows of the output CSV
  std::string out_path;      // the file written; empty when none was asked for or the run did not succeed
  // With keep_geometry (else empty): the edges as read, for a report (pipelines/profile/profile_report.h).
  std::vector<Eigen::Vector3d> edge;
  std::vector<Eigen::Vector3d> second_edge;
};

// The points of an edge CSV. Throws conform::Error naming the file (and the line) when it cannot be read or lacks
// the columns x_mm, y_mm, z_mm, or a value is not a finite number.
std::vector<Eigen::Vector3d> read_profile_edge(const std::string& path);
// The features of a .csv or .json file, in file order. Throws conform::Error naming the file and the line (CSV) or
// the feature (JSON): unknown type, an id that comes back after other features, a missing radius, ...
std::vector<ProfileFeature> read_profile_features(const std::string& path);

// The output CSV text (the columns above, 6 decimals); the same result gives the same bytes.
std::string profile_csv(const ProfileCompensationResult& result);

// Throws conform::Error for bad input (compensate_profile and the readers above); a failed run writes nothing.
ProfileJobResult run_profile(const ProfileJobOptions& options);

}  // namespace conform
