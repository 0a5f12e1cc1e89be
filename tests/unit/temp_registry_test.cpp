// SPDX-License-Identifier: Apache-2.0
// The registry of temporaries a signal handler removes: what it removes, what it leaves, and
// that AtomicFile and the frame-folder sink register theirs while they exist.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/temp_registry.h"
#include "scratch_folder.h"
#include "seqio/sequence_io.h"

namespace animc {
namespace {

namespace fs = std::filesystem;

class TempRegistryTest : public testing_support::ScratchFolderTest {
 protected:
  TempRegistryTest() : ScratchFolderTest("registry") {}
  void touch(const std::string& name) const { std::ofstream(path(name)) << name; }
  size_t entries(const std::string& folder) const {
    return size_t(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
  }
};

TEST_F(TempRegistryTest, RemovesRegisteredFilesAndFoldersOnly) {
  touch("registered.tmp");
  touch("forgotten.tmp");
  touch("kept");
  fs::create_directories(path("folder.tmp"));
  for (int i = 0; i < 300; ++i) touch("folder.tmp/frame_" + std::to_string(i));  // several getdents64 reads
  const int file = registerTemporary(path("registered.tmp"), TemporaryKind::kFile);
  const int forgotten = registerTemporary(path("forgotten.tmp"), TemporaryKind::kFile);
  const int folder = registerTemporary(path("folder.tmp"), TemporaryKind::kFolder);
  ASSERT_GE(file, 0);
  ASSERT_GE(forgotten, 0);
  ASSERT_GE(folder, 0);
  unregisterTemporary(forgotten);
  removeRegisteredTemporaries();
  EXPECT_FALSE(fs::exists(path("registered.tmp")));
  EXPECT_FALSE(fs::exists(path("folder.tmp")));
  EXPECT_TRUE(fs::exists(path("forgotten.tmp")));
  EXPECT_TRUE(fs::exists(path("kept")));
  unregisterTemporary(file);  // taken by the removal: harmless
  unregisterTemporary(folder);
  unregisterTemporary(-1);
}

// A relative path is registered as absolute, so it is found whatever the working folder.
TEST_F(TempRegistryTest, RelativePathsAreMadeAbsolute) {
  const fs::path before = fs::current_path();
  fs::current_path(dir_);
  touch("relative.tmp");
  const int slot = registerTemporary("relative.tmp", TemporaryKind::kFile);
  fs::current_path(before);
  ASSERT_GE(slot, 0);
  removeRegisteredTemporaries();
  EXPECT_FALSE(fs::exists(path("relative.tmp")));
}

TEST_F(TempRegistryTest, AFullTableOrALongPathIsRefused) {
  EXPECT_EQ(registerTemporary("/" + std::string(kMaxTemporaryPathBytes, 'x'), TemporaryKind::kFile), -1);
  std::vector<int> slots;
  for (int slot; (slot = registerTemporary(path("x"), TemporaryKind::kFile)) >= 0;) slots.push_back(slot);
  EXPECT_LE(slots.size(), size_t(kMaxTemporaries));
  // A slot whose temporary removeRegisteredTemporaries() removed stays taken (the process is
  // ending), so the tests before this one may have taken a few.
  EXPECT_GE(slots.size(), size_t(kMaxTemporaries) - 16) << "slots are leaking";
  for (int slot : slots) unregisterTemporary(slot);
  const int again = registerTemporary(path("x"), TemporaryKind::kFile);
  EXPECT_GE(again, 0) << "unregistered slots are reused";
  unregisterTemporary(again);
}

// What a signal handler finds in the middle of a write: the AtomicFile's named temporary (an
// unnamed one leaves nothing to find; named ones are what file systems without O_TMPFILE get),
// and the frame-folder sink's folder with its frames. Once committed or destroyed, nothing is
// left registered (the removal then touches nothing).
TEST_F(TempRegistryTest, WritersRegisterTheirTemporariesWhileTheyExist) {
  {
    setUnnamedTemporaries(false);
    AtomicFile file;
    const Status opened = file.open(path("out.ams"));
    setUnnamedTemporaries(true);
    ASSERT_TRUE(opened.ok());
    ASSERT_TRUE(file.write("x", 1).ok());
    ASSERT_EQ(entries(dir_.string()), 1u);
    removeRegisteredTemporaries();
    EXPECT_EQ(entries(dir_.string()), 0u) << "the AtomicFile's temporary was not registered";
  }
  const Topology triangle{3, {{0, 1, 2}}};
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  {
    auto sink = createSequenceSink(path("frames"), SequenceFormat::kPly, triangle, 25, 3);
    ASSERT_TRUE(sink.ok()) << sink.status().message();
    ASSERT_TRUE(sink.value()->write(xyz.data()).ok());
    ASSERT_TRUE(sink.value()->write(xyz.data()).ok());
    ASSERT_EQ(entries(dir_.string()), 1u);  // the temporary folder
    removeRegisteredTemporaries();
    EXPECT_EQ(entries(dir_.string()), 0u) << "the sink's folder was not registered";
  }
  {
    AtomicFile file;
    ASSERT_TRUE(file.open(path("done.ams")).ok());
    ASSERT_TRUE(file.commit().ok());
    auto sink = createSequenceSink(path("frames"), SequenceFormat::kPly, triangle, 25, 1);
    ASSERT_TRUE(sink.ok());
    ASSERT_TRUE(sink.value()->write(xyz.data()).ok());
    ASSERT_TRUE(sink.value()->finish().ok());
  }
  removeRegisteredTemporaries();
  EXPECT_TRUE(fs::exists(path("done.ams")));
  EXPECT_TRUE(fs::exists(path("frames/frame_00000.ply")));
}

}  // namespace
}  // namespace animc
