// SPDX-License-Identifier: Apache-2.0
// Leftovers of killed runs (core/stale_temporaries.h): which ones the next output into the
// same folder removes, and everything it must leave alone.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/atomic_file.h"
#include "core/stale_temporaries.h"
#include "scratch_folder.h"
#include "seqio/sequence_io.h"
#include "test_sequences.h"

namespace animc {
namespace {

namespace fs = std::filesystem;

// The id of a process that has ended (a child, waited for): no process has it for now.
long endedProcessId() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return long(child);
}

class StaleTemporariesTest : public testing_support::ScratchFolderTest {
 protected:
  StaleTemporariesTest() : ScratchFolderTest("stale") {}

  std::string temporaryName(long pid, int n) const {
    return ".animc-" + std::to_string(pid) + "-" + std::to_string(n) + ".tmp";
  }
  void write(const std::string& name) const { std::ofstream(path(name)) << name; }
  // Sets the modification time `seconds` in the past.
  void age(const std::string& name, long seconds) const {
    fs::last_write_time(path(name), fs::last_write_time(path(name)) - std::chrono::seconds(seconds));
  }
  bool exists(const std::string& name) const { return fs::exists(path(name)); }
};

TEST_F(StaleTemporariesTest, NamesOfTemporariesOnly) {
  long pid = 0;
  EXPECT_TRUE(isTemporaryName(".animc-123-0.tmp", &pid));
  EXPECT_EQ(pid, 123);
  EXPECT_TRUE(isTemporaryName(fs::path(temporaryPathBeside("a/b.ams")).filename().string(), &pid));
  EXPECT_EQ(pid, long(getpid()));
  for (const char* other : {".animc-123-0.tmp.old", ".animc-123.tmp", ".animc--0.tmp", ".animc-12a-0.tmp",
                            "animc-123-0.tmp", ".animc-123-0.tmpx", ".animc-123-.tmp", ".animc-1234567890123-0.tmp"})
    EXPECT_FALSE(isTemporaryName(other, nullptr)) << other;
}

TEST_F(StaleTemporariesTest, RemovesOldLeftoversOfEndedRunsOnly) {
  const long ended = endedProcessId();
  const long old = kStaleTemporarySeconds + 60;
  // Removed: an old file and an old frame folder (with a frame in the making) of an ended run.
  write(temporaryName(ended, 0));
  age(temporaryName(ended, 0), old);
  const std::string folder = temporaryName(ended, 1);
  fs::create_directory(path(folder));
  write(folder + "/frame_00000.ply");
  write(folder + "/frame_00001.obj");  // any frame-file format the sink writes
  write(folder + "/" + temporaryName(ended, 2));
  age(folder, old);
  // Kept: a recent leftover, one of a live process, a folder holding something else, a name
  // outside the pattern (the old frames a fallback swap set aside), and the user's files.
  write(temporaryName(ended, 3));
  write(temporaryName(long(getppid()), 4));
  age(temporaryName(long(getppid()), 4), old);
  fs::create_directory(path(temporaryName(ended, 5)));
  write(temporaryName(ended, 5) + "/notes.txt");
  age(temporaryName(ended, 5), old);
  fs::create_directory(path(temporaryName(ended, 6) + ".old"));
  write(temporaryName(ended, 6) + ".old/frame_00000.ply");
  age(temporaryName(ended, 6) + ".old", old);
  write("frame_00000.ply");
  age("frame_00000.ply", old);

  EXPECT_EQ(removeStaleTemporaries(dir_.string()), 2);
  EXPECT_FALSE(exists(temporaryName(ended, 0)));
  EXPECT_FALSE(exists(folder));
  for (const std::string& kept : {temporaryName(ended, 3), temporaryName(long(getppid()), 4),
                                  temporaryName(ended, 5) + "/notes.txt", temporaryName(ended, 6) + ".old/frame_00000.ply",
                                  std::string("frame_00000.ply")})
    EXPECT_TRUE(exists(kept)) << kept;
}

// The next output into the folder cleans it: a file (through AtomicFile) and a frame folder.
TEST_F(StaleTemporariesTest, TheNextOutputIntoTheFolderRemovesThem) {
  const long ended = endedProcessId();
  for (bool frames : {false, true}) {
    const std::string leftover = temporaryName(ended, frames);
    fs::create_directory(path(leftover));
    write(leftover + "/frame_00000.off");
    age(leftover, kStaleTemporarySeconds + 1);
    const MemorySequence seq = testing_support::gridSequence(3, 3, 2, 1, 1);
    const std::string out = path(frames ? "frames" : "out.pc2");
    auto sink = createSequenceSink(out, frames ? SequenceFormat::kPly : SequenceFormat::kPc2, seq.topology(), 25.0, 2,
                                   ExistingOutput::kRefuse);
    ASSERT_TRUE(sink.ok()) << sink.status().message();
    EXPECT_FALSE(exists(leftover)) << (frames ? "frame folder" : "file");
    for (const auto& frame : seq.frames()) ASSERT_TRUE(sink.value()->write(frame.data()).ok());
    ASSERT_TRUE(sink.value()->finish().ok());
  }
}

}  // namespace
}  // namespace animc
