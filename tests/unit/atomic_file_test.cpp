// SPDX-License-Identifier: Apache-2.0
// AtomicFile on the paths users give: long names, and the temporary names it leaves while it
// writes (the fixed pattern documented in core/atomic_file.h).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "core/atomic_file.h"

namespace animc {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public testing::Test {
 protected:
  void SetUp() override {
    const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(testing::TempDir()) /
           ("atomic_" + std::string(info->name()) + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Names in the test's folder, sorted.
  std::vector<std::string> names(const fs::path& dir) const {
    std::vector<std::string> out;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
      out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
  static std::string contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  fs::path dir_;
};

bool isTemporaryName(const std::string& name) {
  return std::regex_match(name, std::regex(R"(\.animc-[0-9]+-[0-9]+\.tmp)"));
}

// Any name the file system takes, up to NAME_MAX (255) bytes, works: the temporary's name does
// not grow with it.
TEST_F(AtomicFileTest, NamesUpToTheLongestValidOneWork) {
  for (size_t length : {size_t(1), size_t(243), size_t(244), size_t(250), size_t(255)}) {
    const std::string name(length, 'n');
    AtomicFile file;
    Status s = file.open(path(name));
    ASSERT_TRUE(s.ok()) << length << ": " << s.message();
    ASSERT_TRUE(file.write("data", 4).ok());
    ASSERT_TRUE(file.commit().ok()) << length;
    EXPECT_EQ(contents(path(name)), "data") << length;
    fs::remove(path(name));
  }
}

// While it writes, the only new entry in the folder is one temporary with the documented name.
TEST_F(AtomicFileTest, TheTemporaryHasTheDocumentedName) {
  AtomicFile file;
  ASSERT_TRUE(file.open(path("out.ams")).ok());
  const std::vector<std::string> during = names(dir_);
  ASSERT_EQ(during.size(), 1u);
  EXPECT_TRUE(isTemporaryName(during[0])) << during[0];
  EXPECT_NE(during[0].find("-" + std::to_string(getpid()) + "-"), std::string::npos) << during[0];
  ASSERT_TRUE(file.commit().ok());
  EXPECT_EQ(names(dir_), std::vector<std::string>{"out.ams"});
  // Beside a folder named with a trailing '/', the temporary is in the folder's parent.
  fs::create_directories(path("sub"));
  EXPECT_EQ(fs::path(temporaryPathBeside(path("sub/"))).parent_path(), dir_);
  EXPECT_TRUE(isTemporaryName(fs::path(temporaryPathBeside("x.ams")).string()));
}

// A missing folder is reported under the name the caller gave, not the temporary's.
TEST_F(AtomicFileTest, AMissingFolderIsNamed) {
  AtomicFile file;
  Status s = file.open(path("missing/dir/out.ams"));
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_EQ(s.message(), path("missing/dir/out.ams") + ": no such directory " + path("missing/dir"));
  s = file.open("missing/out.ams");
  EXPECT_EQ(s.message(), "missing/out.ams: no such directory missing");
  std::ofstream(path("plain")) << "a file";
  s = file.open(path("plain/out.ams"));
  EXPECT_EQ(s.message(), path("plain/out.ams") + ": " + path("plain") + " is not a directory");
}

}  // namespace
}  // namespace animc
