#include "common/atomic_file.h"
#include "common/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace clearjoint;

TEST(AtomicFile, NothingAppearsBeforeCommit)
{
  test_support::ScratchDir dir("atomic_commit");
  const std::string path = dir.file("out.txt");
  {
    AtomicFile f(path);
    f.stream() << "hello";
    EXPECT_FALSE(std::filesystem::exists(path));
    f.commit();
  }
  EXPECT_EQ(test_support::read_text(path), "hello");
}

TEST(AtomicFile, AbandonedWriteLeavesNoFileAndNoTemporary)
{
  test_support::ScratchDir dir("atomic_abandon");
  {
    AtomicFile f(dir.file("out.txt"));
    f.stream() << "half";
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(AtomicFile, UnwritableDirectoryIsAnInputErrorNamingThePath)
{
  const std::string m =
    test_support::input_error_of([] { AtomicFile f("/nonexistent_dir_clearjoint/out.txt"); });
  EXPECT_NE(m.find("/nonexistent_dir_clearjoint/out.txt"), std::string::npos) << m;
}
