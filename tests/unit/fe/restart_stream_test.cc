// The bytes of a restart file (fe_stage/core/restart_stream.h): values, lists and texts read
// back as written; a reader out of step stops at the next section naming it; a file that ends
// early, or has bytes left over, is an input error naming the file.
#include "fe_stage/core/restart_stream.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <string>

using namespace clearjoint;
using namespace clearjoint::fe;
using clearjoint::test_support::input_error_of;

TEST(RestartStream, ValuesListsAndTextsReadBackAsWritten)
{
  RestartWriter out;
  out.section("first");
  out.put(3.25);
  out.put(7u);
  out.put(true);
  out.put_vector(std::vector<double>{1.0, -2.5, 1e-300});
  out.put_string("rolling");
  out.section("second");
  RestartReader in(out.bytes(), "f.bin");
  in.section("first");
  EXPECT_EQ(in.get<double>(), 3.25);
  EXPECT_EQ(in.get<unsigned int>(), 7u);
  EXPECT_TRUE(in.get<bool>());
  EXPECT_EQ(in.get_vector<double>(), (std::vector<double>{1.0, -2.5, 1e-300}));
  EXPECT_EQ(in.get_string(), "rolling");
  in.section("second");
  EXPECT_NO_THROW(in.expect_end());
}

TEST(RestartStream, AReaderOutOfStepOrAShortFileIsAnInputErrorNamingTheFile)
{
  RestartWriter out;
  out.section("spin stepper");
  out.put_vector(std::vector<double>(10, 1.0));
  const std::string bytes = out.bytes();

  RestartReader wrong(bytes, "state/rank-0.bin");
  const std::string e1 = input_error_of([&] { wrong.section("displacement"); });
  EXPECT_NE(e1.find("state/rank-0.bin"), std::string::npos) << e1;
  EXPECT_NE(e1.find("displacement"), std::string::npos) << e1;

  RestartReader shortened(bytes.substr(0, bytes.size() - 8), "state/rank-1.bin");
  shortened.section("spin stepper");
  const std::string e2 = input_error_of([&] { shortened.get_vector<double>(); });
  EXPECT_NE(e2.find("ends early"), std::string::npos) << e2;
  EXPECT_NE(e2.find("state/rank-1.bin"), std::string::npos) << e2;

  RestartReader left_over(bytes + "x", "f.bin");
  left_over.section("spin stepper");
  left_over.get_vector<double>();
  EXPECT_NE(input_error_of([&] { left_over.expect_end(); }).find("left over"), std::string::npos);
}
