#include "conform/core/csv.h"

#include <clocale>
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "temp_dir.h"

namespace conform {
namespace {

std::string error_of(const std::string& path) {
  try {
    read_csv(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string error_of_number(const std::string& path) {
  try {
    read_csv(path).number(0, 0);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Csv, ToleratesAByteOrderMarkSemicolonsAndUpperCaseNames) {
  // What spreadsheets export: a UTF-8 BOM, CRLF, upper-case names, semicolons as separators.
  test::TempDir dir;
  test::write_bytes(dir.file("s.csv"), "\xEF\xBB\xBFX_MM;Y_MM;Z_mm\r\n1.5;2;3\r\n4;5;6\r\n");
  const CsvTable table = read_csv(dir.file("s.csv"), {"x_mm", "y_mm", "z_mm"});
  ASSERT_EQ(table.rows(), 2u);
  const Eigen::MatrixXd xyz = table.numbers({"x_mm", "y_mm", "z_mm"});
  EXPECT_EQ(xyz(0, 0), 1.5);
  EXPECT_EQ(xyz(1, 2), 6.0);
  // A comma header keeps commas: a semicolon in a cell is then text (and not a number).
  test::write_bytes(dir.file("c.csv"), "x_mm,y_mm\n1;2,3\n");
  EXPECT_TRUE(contains(error_of_number(dir.file("c.csv")), "'1;2'"));
}

TEST(Csv, ParsesTextInMemoryByTheFilesRules) {
  const CsvTable table = parse_csv("\xEF\xBB\xBF# comment\nX_MM;id\r\n1.5;7\n", "memory.csv");
  EXPECT_EQ(table.path, "memory.csv");
  ASSERT_EQ(table.rows(), 1u);
  EXPECT_EQ(table.line_numbers, (std::vector<std::size_t>{3}));
  EXPECT_EQ(table.number(0, table.column("x_mm")), 1.5);
  EXPECT_EQ(table.integer(0, table.column("id")), 7);
  try {
    parse_csv("a,b\n1\n", "memory.csv");
    ADD_FAILURE() << "a short row was accepted";
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "memory.csv:2: 1 fields")) << e.what();
  }
}

TEST(Csv, ReadsHeaderRowsAndNumbersSkippingCommentsAndBlankLines) {
  test::TempDir dir;
  test::write_bytes(dir.file("t.csv"), "# made by hand\n x_mm , y_mm,\"id\"\r\n\n1.5, -2e3 ,7\n# note\n0,0.25,8\n");
  const CsvTable table = read_csv(dir.file("t.csv"), {"x_mm", "id"});
  ASSERT_EQ(table.columns, (std::vector<std::string>{"x_mm", "y_mm", "id"}));
  ASSERT_EQ(table.rows(), 2u);
  EXPECT_EQ(table.line_numbers, (std::vector<std::size_t>{4, 6}));
  EXPECT_EQ(table.number(0, 0), 1.5);
  EXPECT_EQ(table.number(0, 1), -2000.0);
  EXPECT_EQ(table.integer(1, table.column("id")), 8);
  const Eigen::MatrixXd xy = table.numbers({"y_mm", "x_mm"});
  ASSERT_EQ(xy.rows(), 2);
  EXPECT_EQ(xy(1, 0), 0.25);
  EXPECT_EQ(xy(0, 1), 1.5);
}

TEST(Csv, BadCellsNameFileLineAndColumn) {
  test::TempDir dir;
  test::write_bytes(dir.file("t.csv"), "a,b\n1,2\n3,abc\n4,nan\n5,1.5\n");
  const CsvTable table = read_csv(dir.file("t.csv"));
  try {
    table.number(1, 1);
    FAIL();
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), dir.file("t.csv") + ":3: column 'b'")) << e.what();
    EXPECT_TRUE(contains(e.what(), "abc")) << e.what();
  }
  EXPECT_THROW(table.number(2, 1), Error);   // nan is not finite
  EXPECT_THROW(table.integer(3, 1), Error);  // 1.5 is not whole
  EXPECT_EQ(table.number(3, 1), 1.5);
  // Beyond +-1e7 (10 km in mm): a broken file, not a coordinate (a 1e300 point printed 300 digits into a program).
  const CsvTable far = parse_csv("x,y\n1e7,-1e7\n1e300,0\n0,-1.0000001e7\n", "far.csv");
  EXPECT_EQ(far.number(0, 0), 1e7);
  EXPECT_EQ(far.number(0, 1), -1e7);
  try {
    far.number(1, 0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "far.csv:3: column 'x': '1e300' is beyond")) << e.what();
  }
  EXPECT_THROW(far.number(2, 1), Error);
  try {
    table.column("c");
    FAIL();
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "no column 'c' (the header has: a,b)")) << e.what();
  }
}

TEST(Csv, MalformedFilesAreErrorsNamingTheProblem) {
  test::TempDir dir;
  test::write_bytes(dir.file("ragged.csv"), "a,b,c\n1,2,3\n1,2\n");
  EXPECT_TRUE(contains(error_of(dir.file("ragged.csv")), "ragged.csv:3: 2 fields, but the header names 3"));
  test::write_bytes(dir.file("empty.csv"), "# only a comment\n\n");
  EXPECT_TRUE(contains(error_of(dir.file("empty.csv")), "no header line"));
  test::write_bytes(dir.file("dup.csv"), "a,b,a\n");
  EXPECT_TRUE(contains(error_of(dir.file("dup.csv")), "column 'a' appears twice"));
  test::write_bytes(dir.file("noname.csv"), "a,,b\n");
  EXPECT_TRUE(contains(error_of(dir.file("noname.csv")), "column 2 has no name"));
  EXPECT_TRUE(contains(error_of(dir.file("missing.csv")), "missing.csv"));
  test::write_bytes(dir.file("cols.csv"), "x_mm,z_mm\n1,2\n");
  try {
    read_csv(dir.file("cols.csv"), {"x_mm", "y_mm", "z_mm"});
    FAIL();
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "missing column(s) y_mm")) << e.what();
  }
}

TEST(Csv, WriterIsDeterministicAndRoundTrips) {
  test::TempDir dir;
  CsvWriter writer({"id", "x_mm", "kind"}, 3);
  writer.cell(1).cell(-0.0001).cell("circle");
  writer.end_row();
  writer.cell(std::int64_t{-2}).cell(12345.6789).cell("point");
  writer.end_row();
  EXPECT_EQ(writer.text(), "id,x_mm,kind\n1,0.000,circle\n-2,12345.679,point\n");
  EXPECT_EQ(writer.rows(), 2u);
  writer.write(dir.file("out.csv"));
  const CsvTable table = read_csv(dir.file("out.csv"));
  EXPECT_NEAR(table.number(1, 1), 12345.6789, 0.0005);
  EXPECT_EQ(table.text(0, 2), "circle");
}

TEST(Csv, WriterIgnoresTheLocaleAndRefusesMisuse) {
  // A locale with a decimal comma must not change the bytes (skipped silently where none is installed).
  const char* previous = std::setlocale(LC_NUMERIC, nullptr);
  const std::string saved = previous ? previous : "C";
  std::setlocale(LC_NUMERIC, "de_DE.UTF-8");
  EXPECT_EQ(format_fixed(1.25, 2), "1.25");
  std::setlocale(LC_NUMERIC, saved.c_str());
  EXPECT_EQ(format_fixed(-0.0, 1), "0.0");
  EXPECT_EQ(format_fixed(-0.04, 1), "0.0");
  EXPECT_EQ(format_fixed(-0.06, 1), "-0.1");

  CsvWriter writer({"a", "b"});
  writer.cell(1.0);
  EXPECT_THROW(writer.end_row(), std::logic_error);
  EXPECT_THROW(writer.write("/tmp/never-written.csv"), Error);
  writer.cell(2.0);
  EXPECT_THROW(writer.cell(3.0), std::logic_error);
  EXPECT_THROW(CsvWriter({"a"}).cell("x,y"), Error);
}

}  // namespace
}  // namespace conform
