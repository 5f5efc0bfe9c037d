#include "conform/core/transform_io.h"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "io_test_data.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::error_of;
using test::read_bytes;
using test::write_bytes;

Eigen::Isometry3d random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1234.5;
  return T;
}

// Tolerance: none; 17 significant digits give every double back, and an exact rotation is not re-orthonormalised.
TEST(TransformIo, RoundTripGivesTheSameDoubles) {
  test::TempDir dir;
  std::mt19937 rng(3);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Isometry3d T = random_pose(rng);
    write_transform(dir.file("T.txt"), T);
    EXPECT_EQ(read_transform(dir.file("T.txt")).matrix(), T.matrix());
  }
  EXPECT_EQ(dir.listing(), "T.txt\n");
}

TEST(TransformIo, WrittenAsFourRowsSameBytesEachTime) {
  test::TempDir dir;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.1, -2, 300);
  write_transform(dir.file("a.txt"), T);
  write_transform(dir.file("b.txt"), T);
  EXPECT_EQ(read_bytes(dir.file("a.txt")), "1 0 0 0.10000000000000001\n0 1 0 -2\n0 0 1 300\n0 0 0 1\n");
  EXPECT_EQ(read_bytes(dir.file("a.txt")), read_bytes(dir.file("b.txt")));
}

TEST(TransformIo, CloudCompareFileWithTrailingSpaceAndBlankLines) {
  test::TempDir dir;
  // A rotation of 30 degrees about z, as CloudCompare writes it: 12 decimals, a space at the end of each line.
  write_bytes(dir.file("cc.txt"),
              "0.866025403784 -0.500000000000 0.000000000000 10.000000000000 \r\n"
              "0.500000000000 0.866025403784 0.000000000000 -20.500000000000 \r\n"
              "0.000000000000 0.000000000000 1.000000000000 0.250000000000 \r\n"
              "0.000000000000 0.000000000000 0.000000000000 1.000000000000 \r\n"
              "\n\n");
  const Eigen::Isometry3d T = read_transform(dir.file("cc.txt"));
  const double angle = std::acos(-1.0) / 6;
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Eigen::Matrix3d R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  // Tolerance: the file's 12 decimals.
  EXPECT_LT((T.linear() - R).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(T.translation(), Eigen::Vector3d(10, -20.5, 0.25));
  // Re-orthonormalised to double precision.
  EXPECT_LT((T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(TransformIo, MalformedFilesAreErrorsNamingFileAndLine) {
  test::TempDir dir;
  const std::string identity = "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {identity + "5\n", ":5: more than 16 numbers"},
      {"1 0 0 0 7\n0 1 0 0\n0 0 1 0\n0 0 0 1\n", ":1: more than 4 numbers in row 1"},
      {"1 0 0 0\n0 1 0\n0 0 1 0\n0 0 0 1\n", ":2: row 2 has 3 numbers, not 4"},
      {"1 0 0 0\n0 1 0 0\n0 0 1 0\n", "holds 3 rows of numbers"},
      {"1 0 0 0\n0 1 0 0\n0 0 one 0\n0 0 0 1\n", ":3: column 3: 'one' is not a number"},
      {"1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 1 1\n", "the last row is not 0 0 0 1"},
      {"2 0 0 0\n0 2 0 0\n0 0 2 0\n0 0 0 1\n", "the upper-left 3x3 is not a rotation"},
      {"-1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n", "the upper-left 3x3 is not a rotation"},
      {"1 0 0 nan\n0 1 0 0\n0 0 1 0\n0 0 0 1\n", "NaN or infinite"},
      {"", "is empty"},
  };
  for (const auto& c : cases) {
    write_bytes(dir.file("T.txt"), c.text);
    const std::string message = error_of([&] { read_transform(dir.file("T.txt")); });
    EXPECT_CONTAINS(message, dir.file("T.txt"));
    EXPECT_CONTAINS(message, c.expected);
  }
  EXPECT_CONTAINS(error_of([&] { read_transform(dir.file("missing.txt")); }), "No such file or directory");
}

}  // namespace
}  // namespace conform
