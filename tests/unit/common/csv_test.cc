#include "common/csv.h"
#include "common/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint;

TEST(Csv, WriterAndReaderRoundTripWithUnitsAndStatus)
{
  test_support::ScratchDir dir("csv_roundtrip");
  const std::string path = dir.file("t.csv");
  CsvWriter w(path, {"delta", "force"}, {"m", "N"}, {"made by a test"});
  w.write_row({0.0, 0.0});
  w.write_row({1.0 / 3.0, 338240.123456789});
  EXPECT_FALSE(std::filesystem::exists(path)) << "visible before commit";
  w.commit();
  const CsvTable t = read_csv(path);
  ASSERT_EQ(t.columns.size(), 2u);
  EXPECT_EQ(t.unit_of("delta"), "m");
  EXPECT_EQ(t.unit_of("force"), "N");
  EXPECT_EQ(t.status, "complete");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[1][0], 1.0 / 3.0);  // 17 digits: lossless
  EXPECT_EQ(t.rows[1][1], 338240.123456789);
  EXPECT_EQ(t.comments.at(0), "made by a test");
}

TEST(Csv, IncompleteRunIsMarked)
{
  test_support::ScratchDir dir("csv_incomplete");
  CsvWriter w(dir.file("t.csv"), {"a"}, {"1"});
  w.write_row({1.0});
  w.commit_incomplete("increment 3 did not converge");
  EXPECT_EQ(read_csv(dir.file("t.csv")).status, "incomplete: increment 3 did not converge");
}

TEST(Csv, ReaderAcceptsWhitespaceDataButNoNonFiniteValues)
{
  test_support::ScratchDir dir("csv_ws");
  test_support::write_text(dir.file("t.txt"), "# comment\nx y\n1.5 2\n-3e-4 3\n");
  const CsvTable t = read_csv(dir.file("t.txt"));
  EXPECT_TRUE(t.units.empty());
  EXPECT_EQ(t.rows[0][0], 1.5);
  EXPECT_EQ(t.rows[1][0], -3e-4);
  // nan, inf and overflowing numbers would flow into a fit: input errors naming line and column.
  for (const std::string bad : {"nan", "inf", "-infinity", "1e400"})
  {
    test_support::write_text(dir.file("b.txt"), "x y\n1.5 2\n" + bad + " 3\n");
    const std::string m = test_support::input_error_of([&] { read_csv(dir.file("b.txt")); });
    EXPECT_NE(m.find("line 3, column 'x'"), std::string::npos) << bad << ": " << m;
  }
  test_support::write_text(dir.file("d.csv"), "delta,delta\n1,2\n");
  EXPECT_THROW(read_csv(dir.file("d.csv")), InputError) << "a column named twice";
  test_support::write_text(dir.file("u.csv"), "delta,f\xffrce\n1,2\n");
  EXPECT_THROW(read_csv(dir.file("u.csv")), InputError) << "bytes that are not UTF-8";
}

TEST(Csv, RaggedRowAndNonNumberNameFileAndLine)
{
  test_support::ScratchDir dir("csv_bad");
  test_support::write_text(dir.file("a.csv"), "delta,force\n1,2\n3\n");
  test_support::write_text(dir.file("b.csv"), "delta,force\n1,abc\n");
  const std::string a = test_support::input_error_of([&] { read_csv(dir.file("a.csv")); });
  EXPECT_NE(a.find("line 3"), std::string::npos) << a;
  const std::string b = test_support::input_error_of([&] { read_csv(dir.file("b.csv")); });
  EXPECT_NE(b.find("'force'"), std::string::npos) << b;
  EXPECT_NE(b.find("abc"), std::string::npos) << b;
}

TEST(Csv, MissingColumnListsTheColumnsPresent)
{
  test_support::ScratchDir dir("csv_missing");
  test_support::write_text(dir.file("a.csv"), "delta,load\n1,2\n");
  const CsvTable t = read_csv(dir.file("a.csv"));
  const std::string m = test_support::input_error_of([&] { t.column("force"); });
  EXPECT_NE(m.find("delta, load"), std::string::npos) << m;
}
