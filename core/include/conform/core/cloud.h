#pragma once
// A point cloud in millimetres: PCL float points with optional unit normals (one per point).

#include <cstddef>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace conform {

struct Cloud {
  pcl::PointCloud<pcl::PointXYZ> points;  // mm
  pcl::PointCloud<pcl::Normal> normals;   // empty, or one unit normal per point (curvature = surface variation)

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_normals() const { return !normals.empty(); }
};

// Throws conform::Error (naming `what`) when normals are present but not one per point.
void check_consistent(const Cloud& cloud, const char* what);

}  // namespace conform
