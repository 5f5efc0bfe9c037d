#include "conform/core/transform_io.h"

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include <Eigen/SVD>

#include "conform/core/atomic_file.h"
#include "conform/core/error.h"
#include "file_bytes.h"
#include "text_scanner.h"

namespace conform {

namespace {

// Tolerances for what counts as a rigid transform; CloudCompare writes 12 decimals, far inside them.
constexpr double kRotationTolerance = 1e-6;
constexpr double kLastRowTolerance = 1e-9;
// Below this, R is orthonormal as far as doubles can tell (a rotation computed in double is off by ~1e-16).
constexpr double kRoundingTolerance = 1e-14;

Eigen::Matrix4d read_matrix(const std::string& path) {
  const detail::FileBytes bytes = detail::read_file_bytes(path);
  detail::LineScanner lines(bytes.view());
  Eigen::Matrix4d m;
  int rows = 0;
  std::string_view line;
  while (lines.next(line)) {
    std::string_view rest = line;
    std::string_view token;
    int columns = 0;
    const std::string where = path + ":" + std::to_string(lines.line_number()) + ": ";
    while (detail::next_token(rest, token)) {
      if (rows == 4) throw Error(where + "more than 16 numbers (a transform is 4 rows of 4)");
      if (columns == 4) throw Error(where + "more than 4 numbers in row " + std::to_string(rows + 1));
      if (!detail::parse_number(token, m(rows, columns))) {
        throw Error(where + "column " + std::to_string(columns + 1) + ": " + detail::describe_bad_number(token));
      }
      ++columns;
    }
    if (columns == 0) continue;  // blank lines, e.g. at the end
    if (columns < 4) {
      throw Error(where + "row " + std::to_string(rows + 1) + " has " + std::to_string(columns) + " numbers, not 4");
    }
    ++rows;
  }
  if (rows < 4) {
    throw Error(path + ": holds " + std::to_string(rows) + " rows of numbers; a transform is 4 rows of 4");
  }
  return m;
}

}  // namespace

Eigen::Isometry3d read_transform(const std::string& path) {
  const Eigen::Matrix4d m = read_matrix(path);
  if (!m.allFinite()) throw Error(path + ": the matrix has NaN or infinite entries");
  const Eigen::RowVector4d last = m.row(3);
  if ((last - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > kLastRowTolerance) {
    throw Error(path + ": the last row is not 0 0 0 1 (not a rigid transform)");
  }
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  const double orthogonality = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = R.determinant();
  if (orthogonality > kRotationTolerance || std::abs(det - 1.0) > kRotationTolerance) {
    throw Error(path + ": the upper-left 3x3 is not a rotation (|R^T R - I| = " + std::to_string(orthogonality) +
                ", det = " + std::to_string(det) + "); scaled or mirrored transforms are not rigid");
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = m.topRightCorner<3, 1>();
  // The nearest rotation (polar decomposition, R = U V^T), so that 12-decimal files give a rotation to double
  // precision. Skipped when R is one already, so that what write_transform() wrote reads back bit for bit.
  if (orthogonality > kRoundingTolerance || std::abs(det - 1.0) > kRoundingTolerance) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    T.linear() = svd.matrixU() * svd.matrixV().transpose();
  }
  return T;
}

void write_transform(const std::string& path, const Eigen::Isometry3d& T) {
  const Eigen::Matrix4d m = T.matrix();
  std::string text;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      char number[32];
      // 17 significant digits give every double back exactly; to_chars ignores the locale.
      const std::to_chars_result result =
          std::to_chars(number, number + sizeof(number), m(r, c), std::chars_format::general, 17);
      if (c > 0) text += ' ';
      text.append(number, result.ptr);
    }
    text += '\n';
  }
  write_file_atomically(path, text);
}

}  // namespace conform
