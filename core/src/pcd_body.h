#pragma once
// The body of a PCD file, decoded by conform itself after parse_pcd_header(): every value checked against its field's
// TYPE and SIZE, every read bounds-checked, the body's size matched exactly against the header.

#include <string>
#include <string_view>

#include "conform/core/mesh.h"
#include "pcd_header.h"

namespace conform::detail {

// The points (x y z) and, when the file has normal_x, normal_y and normal_z, their normals. `body` is everything after
// the DATA line. Throws conform::Error "path:line: field 'name': ..." (ascii) or "path: ..." (binary) when the body does
// not hold exactly header.points points, a value does not fit its field, or compressed data is damaged.
Mesh decode_pcd_body(const std::string& path, const PcdHeader& header, std::string_view body);

}  // namespace conform::detail
