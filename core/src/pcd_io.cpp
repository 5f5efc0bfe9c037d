// PCD through PCL's reader and writer (the format is PCL's own), after check_pcd() has made sure that the file is
// one PCL reads correctly and quietly. Writing goes through a pcl::PCLPointCloud2 built here with exactly the fields
// x y z [normal_x normal_y normal_z], packed: pcl::PointNormal would carry padding bytes of undefined content, and
// the same cloud must always give the same bytes.

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include "conform/core/atomic_file.h"
#include "conform/core/error.h"
#include "file_bytes.h"
#include "io_formats.h"
#include "pcd_header.h"

namespace conform::detail {

namespace {

template <typename T>
double as_double(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));  // PCL's point data has no alignment guarantee for every field
  return static_cast<double>(value);
}

// PCL keeps the values in the host's byte order, whatever the file's.
double value_at(const std::uint8_t* p, std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8:
      return as_double<std::int8_t>(p);
    case pcl::PCLPointField::UINT8:
      return as_double<std::uint8_t>(p);
    case pcl::PCLPointField::INT16:
      return as_double<std::int16_t>(p);
    case pcl::PCLPointField::UINT16:
      return as_double<std::uint16_t>(p);
    case pcl::PCLPointField::INT32:
      return as_double<std::int32_t>(p);
    case pcl::PCLPointField::UINT32:
      return as_double<std::uint32_t>(p);
    case pcl::PCLPointField::FLOAT32:
      return as_double<float>(p);
    case pcl::PCLPointField::FLOAT64:
      return as_double<double>(p);
    default:
      return 0.0;  // check_pcd() lets no other type through
  }
}

const pcl::PCLPointField* find_field(const pcl::PCLPointCloud2& blob, const char* name) {
  for (const pcl::PCLPointField& f : blob.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

std::vector<Eigen::Vector3d> extract(const pcl::PCLPointCloud2& blob, const pcl::PCLPointField* const (&field)[3]) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(std::size_t{blob.width} * blob.height);
  for (std::size_t row = 0; row < blob.height; ++row) {
    const std::uint8_t* point = blob.data.data() + row * blob.row_step;
    for (std::size_t col = 0; col < blob.width; ++col, point += blob.point_step) {
      out.emplace_back(value_at(point + field[0]->offset, field[0]->datatype),
                       value_at(point + field[1]->offset, field[1]->datatype),
                       value_at(point + field[2]->offset, field[2]->datatype));
    }
  }
  return out;
}

pcl::PCLPointCloud2 to_blob(const Cloud& cloud) {
  pcl::PCLPointCloud2 blob;
  const char* const names[] = {"x", "y", "z", "normal_x", "normal_y", "normal_z"};
  const std::size_t fields = cloud.has_normals() ? 6 : 3;
  for (std::size_t i = 0; i < fields; ++i) {
    pcl::PCLPointField f;
    f.name = names[i];
    f.offset = static_cast<std::uint32_t>(i * sizeof(float));
    f.datatype = pcl::PCLPointField::FLOAT32;
    f.count = 1;
    blob.fields.push_back(f);
  }
  blob.width = static_cast<std::uint32_t>(cloud.size());
  blob.height = 1;
  blob.point_step = static_cast<std::uint32_t>(fields * sizeof(float));
  blob.row_step = blob.point_step * blob.width;
  blob.is_dense = false;
  blob.data.resize(std::size_t{blob.row_step});
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    float values[6] = {cloud.points[i].x, cloud.points[i].y, cloud.points[i].z, 0, 0, 0};
    if (cloud.has_normals()) {
      values[3] = cloud.normals[i].normal_x;
      values[4] = cloud.normals[i].normal_y;
      values[5] = cloud.normals[i].normal_z;
    }
    std::memcpy(blob.data.data() + i * blob.point_step, values, blob.point_step);
  }
  return blob;
}

// PCL refuses to write a cloud without points (and prints about it), so an empty cloud's header is written here,
// the same header PCL writes.
std::string empty_pcd(bool normals, bool ascii) {
  return std::string("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n") +
         (normals ? "FIELDS x y z normal_x normal_y normal_z\nSIZE 4 4 4 4 4 4\nTYPE F F F F F F\nCOUNT 1 1 1 1 1 1\n"
                  : "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n") +
         "WIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\nDATA " + (ascii ? "ascii\n" : "binary\n");
}

}  // namespace

Mesh read_pcd(const std::string& path, ReadReport& /*report*/) {
  const PcdHeader header = check_pcd(path, read_file_bytes(path).view());
  Mesh mesh;
  if (header.points == 0) return mesh;  // PCL prints a complaint about empty files; there is nothing to read anyway

  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0;
  int status = -1;
  try {
    status = pcl::PCDReader().read(path, blob, origin, orientation, version);
  } catch (const std::exception& e) {
    throw Error(path + ": " + e.what());
  }
  // Only a damaged binary_compressed payload or a file changed since check_pcd() gets here.
  if (status != 0) throw Error(path + ": PCL's PCD reader could not read the file (damaged compressed data?)");
  const pcl::PCLPointField* const xyz[3] = {find_field(blob, "x"), find_field(blob, "y"), find_field(blob, "z")};
  const pcl::PCLPointField* const normal[3] = {find_field(blob, "normal_x"), find_field(blob, "normal_y"),
                                               find_field(blob, "normal_z")};
  if (xyz[0] == nullptr || xyz[1] == nullptr || xyz[2] == nullptr) throw Error(path + ": no x, y, z fields");
  mesh.vertices = extract(blob, xyz);
  if (normal[0] != nullptr && normal[1] != nullptr && normal[2] != nullptr) mesh.normals = extract(blob, normal);
  return mesh;
}

void write_pcd(const std::string& path, const Cloud& cloud, const WriteOptions& options) {
  const bool ascii = options.encoding == Encoding::kAscii;
  if (cloud.empty()) return write_file_atomically(path, empty_pcd(cloud.has_normals(), ascii));
  // Created here first (AtomicFile: O_EXCL, a random name) so that an unwritable place is our error with its reason,
  // not a message PCL prints; PCL then writes the temporary by name.
  AtomicFile file(path);
  const pcl::PCLPointCloud2 blob = to_blob(cloud);
  pcl::PCDWriter writer;
  int status = -1;
  try {
    // Precision 9: the shortest that gives every float back unchanged.
    status = ascii
                 ? writer.writeASCII(file.temp_path(), blob, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), 9)
                 : writer.writeBinary(file.temp_path(), blob);
  } catch (const std::exception& e) {
    throw Error(path + ": cannot write (" + e.what() + ")");
  }
  if (status != 0) throw Error(path + ": cannot write (PCL's PCD writer failed)");
  file.commit();
}

}  // namespace conform::detail
