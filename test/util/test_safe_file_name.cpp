#include "surface_nbv/util/safe_file_name.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace surface_nbv;
namespace fs = std::filesystem;

class SafeFileName : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() / "surface_nbv_safe_name_test").string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ + "/real.map") << "x";
    std::ofstream("/tmp/surface_nbv_outside.map") << "secret";
    ASSERT_EQ(symlink("/tmp/surface_nbv_outside.map", (dir_ + "/link.map").c_str()), 0);
    fs::create_directories(dir_ + "/sub");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string dir_;
};

TEST_F(SafeFileName, AcceptsPlainNames) {
  std::string path;
  ASSERT_TRUE(resolveFileName(dir_, "new.map", false, &path).ok());
  EXPECT_EQ(path, dir_ + "/new.map");
  ASSERT_TRUE(resolveFileName(dir_, "real.map", true, &path).ok());
  EXPECT_EQ(path, dir_ + "/real.map");
}

TEST_F(SafeFileName, RefusesPathsTraversalAndSymlinks) {
  std::string path = "untouched";
  for (const std::string& bad : {std::string(""), std::string(".."), std::string("."), std::string("../x.map"),
                                 std::string("/etc/passwd"), std::string("a/b.map"), std::string("a\\b"),
                                 std::string(".hidden"), std::string("link.map"), std::string("sub"),
                                 std::string("new\nline"), std::string(200, 'a')}) {
    const Status s = resolveFileName(dir_, bad, false, &path);
    EXPECT_FALSE(s.ok()) << "accepted '" << bad << "'";
    EXPECT_FALSE(s.message().empty());
  }
  EXPECT_EQ(path, "untouched");
  EXPECT_FALSE(resolveFileName(dir_, "missing.map", true, &path).ok());
  EXPECT_FALSE(resolveFileName("", "x.map", false, &path).ok());
}

// A writer writes <name>.tmp and renames it: a link planted at that name is
// refused for writing (it would be followed), a leftover regular file is not.
TEST_F(SafeFileName, RefusesALinkPlantedAtTheTemporaryName) {
  ASSERT_EQ(symlink("/tmp/surface_nbv_outside.map", (dir_ + "/planted.map.tmp").c_str()), 0);
  std::string path = "untouched";
  const Status s = resolveFileName(dir_, "planted.map", false, &path);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("temporary"), std::string::npos) << s.message();
  EXPECT_EQ(path, "untouched");
  fs::create_directories(dir_ + "/dir.map.tmp");
  EXPECT_FALSE(resolveFileName(dir_, "dir.map", false, &path).ok());
  std::ofstream(dir_ + "/left.map.tmp") << "partial";
  EXPECT_TRUE(resolveFileName(dir_, "left.map", false, &path).ok());
  EXPECT_FALSE(resolveFileName(dir_, "planted.map.tmp", true, &path).ok());  // a link, even to read
}
