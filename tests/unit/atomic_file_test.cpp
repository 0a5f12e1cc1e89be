// SPDX-License-Identifier: Apache-2.0
// AtomicFile on the paths users give: long names, devices and FIFOs, and the temporary names
// it leaves while it writes (the fixed pattern documented in core/atomic_file.h).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "core/atomic_file.h"
#include "scratch_folder.h"

namespace animc {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public testing_support::ScratchFolderTest {
 protected:
  AtomicFileTest() : ScratchFolderTest("atomic") {}
};

// The names in a folder, sorted.
std::vector<std::string> names(const fs::path& dir) {
  std::vector<std::string> out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

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

// Whether the file system under `dir` makes unnamed files (O_TMPFILE).
bool hasUnnamedFiles(const fs::path& dir) {
#ifdef O_TMPFILE
  const int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd < 0) return false;
  ::close(fd);
  return true;
#else
  (void)dir;
  return false;
#endif
}

// While it writes, the folder holds no new entry where the file system makes unnamed files,
// else one temporary with the documented name; named temporaries (also the name an unnamed one
// gets for its rename) match the documented pattern.
TEST_F(AtomicFileTest, TheTemporaryIsUnnamedOrHasTheDocumentedName) {
  AtomicFile file;
  ASSERT_TRUE(file.open(path("out.ams")).ok());
  ASSERT_TRUE(file.write("data", 4).ok());
  const std::vector<std::string> during = names(dir_);
  if (hasUnnamedFiles(dir_)) {
    EXPECT_TRUE(during.empty()) << during[0];
  } else {
    ASSERT_EQ(during.size(), 1u);
    EXPECT_TRUE(isTemporaryName(during[0])) << during[0];
    EXPECT_NE(during[0].find("-" + std::to_string(getpid()) + "-"), std::string::npos) << during[0];
  }
  ASSERT_TRUE(file.commit().ok());
  EXPECT_EQ(names(dir_), std::vector<std::string>{"out.ams"});
  EXPECT_EQ(contents(path("out.ams")), "data");
  // Beside a folder named with a trailing '/', the temporary is in the folder's parent.
  fs::create_directories(path("sub"));
  EXPECT_EQ(fs::path(temporaryPathBeside(path("sub/"))).parent_path(), dir_);
  EXPECT_TRUE(isTemporaryName(fs::path(temporaryPathBeside("x.ams")).string()));
}

// A writer killed before commit (SIGKILL: no handler, no destructor) leaves nothing behind
// where the file system makes unnamed files, and the old file stays whole.
TEST_F(AtomicFileTest, AKilledWriterLeavesNothingBehind) {
  if (!hasUnnamedFiles(dir_)) GTEST_SKIP() << "the file system under " << dir_ << " has no O_TMPFILE";
  std::ofstream(path("out.ams")) << "old";
  const pid_t child = fork();
  ASSERT_GE(child, 0) << std::strerror(errno);
  if (child == 0) {
    AtomicFile file;
    const std::string block(1 << 20, 'x');
    if (file.open(path("out.ams")).ok() && file.write(block.data(), block.size()).ok()) kill(getpid(), SIGKILL);
    _exit(1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the writer failed before it was killed";
  EXPECT_EQ(names(dir_), std::vector<std::string>{"out.ams"});
  EXPECT_EQ(contents(path("out.ams")), "old");
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

bool isCharacterDevice(const std::string& path) {
  struct stat st;
  return lstat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

// A private null device: as root a test must not risk the system's /dev/null (the old code
// renamed a regular file over it). Others cannot create one, nor replace /dev/null.
std::string nullDevice(const std::string& private_path) {
  if (geteuid() != 0) return "/dev/null";
  EXPECT_EQ(mknod(private_path.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0) << std::strerror(errno);
  return private_path;
}

// A device is written in place, never renamed over: it stays a device and no temporary is
// made beside it. Positions are counted by AtomicFile (/dev/null reports 0 for any).
TEST_F(AtomicFileTest, ACharacterDeviceIsWrittenInPlace) {
  const std::string null = nullDevice(path("null"));
  ASSERT_TRUE(isCharacterDevice(null)) << null;
  for (bool commit : {true, false}) {
    AtomicFile file;
    Status s = file.open(null);
    ASSERT_TRUE(s.ok()) << s.message();
    ASSERT_TRUE(file.write("hello world", 11).ok());
    EXPECT_EQ(file.tell(), 11u);
    ASSERT_TRUE(file.seek(4).ok());
    EXPECT_EQ(file.tell(), 4u);
    if (commit) {
      EXPECT_TRUE(file.commit().ok());
    }
  }
  EXPECT_TRUE(isCharacterDevice(null)) << null << " was replaced";
  EXPECT_EQ(names(dir_).size(), geteuid() == 0 ? 1u : 0u) << "a temporary was left";
}

// A FIFO cannot seek, but writers patch headers: the reader at the other end gets the final
// bytes, the FIFO stays a FIFO, nothing is left beside it.
TEST_F(AtomicFileTest, AFifoGetsTheFinalBytes) {
  const std::string fifo = path("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  // A second name for the FIFO, to release the reader should the writer replace "fifo".
  ASSERT_EQ(link(fifo.c_str(), path("fifo_link").c_str()), 0) << std::strerror(errno);
  std::string received;
  std::thread reader([&] { received = contents(fifo); });  // open() blocks until both ends are
  {
    AtomicFile file;
    Status s = file.open(fifo);
    EXPECT_TRUE(s.ok()) << s.message();
    if (s.ok()) {
      EXPECT_TRUE(file.write("hello world", 11).ok());
      EXPECT_TRUE(file.seek(0).ok());
      EXPECT_TRUE(file.write("J", 1).ok());
      EXPECT_EQ(file.tell(), 1u);
      EXPECT_TRUE(file.commit().ok());
    }
  }
  struct stat st;
  const bool still_fifo = lstat(fifo.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
  if (!still_fifo) ::close(::open(path("fifo_link").c_str(), O_WRONLY | O_NONBLOCK));
  reader.join();
  EXPECT_TRUE(still_fifo) << "the FIFO was replaced";
  EXPECT_EQ(received, "Jello world");
  EXPECT_EQ(names(dir_), (std::vector<std::string>{"fifo", "fifo_link"}));
}

TEST_F(AtomicFileTest, AFolderIsRefused) {
  fs::create_directories(path("folder"));
  AtomicFile file;
  Status s = file.open(path("folder"));
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_EQ(s.message(), path("folder") + ": is a directory");
  EXPECT_EQ(names(dir_), std::vector<std::string>{"folder"});
}

bool isLink(const std::string& path) {
  std::error_code ec;
  return fs::is_symlink(fs::symlink_status(path, ec));
}

// Named temporaries while it lives, as on a file system without O_TMPFILE.
struct NamedTemporaries {
  NamedTemporaries() { setUnnamedTemporaries(false); }
  ~NamedTemporaries() { setUnnamedTemporaries(true); }
};

// A symbolic link stays a link: the file it leads to (through every link, relative links
// against their own folder) gets the new content, with the temporary beside that file (a
// rename across file systems would fail), named or not.
void checkLinksStayLinks(const fs::path& dir, bool unnamed) {
  auto path = [&](const std::string& name) { return (dir / name).string(); };
  fs::create_directories(path("real"));
  std::ofstream(path("real/out.ams")) << "old";
  fs::create_symlink("real/out.ams", path("link1.ams"));
  fs::create_symlink(path("link1.ams"), path("link2.ams"));  // absolute, to a link
  const std::vector<std::string> top = {"link1.ams", "link2.ams", "real"};
  for (const char* link : {"link1.ams", "link2.ams"}) {
    AtomicFile file;
    Status s = file.open(path(link));
    ASSERT_TRUE(s.ok()) << s.message();
    ASSERT_TRUE(file.write(link, 9).ok());
    EXPECT_EQ(names(dir), top);
    const std::vector<std::string> beside_target = names(path("real"));
    if (!unnamed || !hasUnnamedFiles(path("real"))) {
      ASSERT_EQ(beside_target.size(), 2u) << "no temporary beside the target";
      EXPECT_TRUE(isTemporaryName(beside_target[0])) << beside_target[0];
    }
    ASSERT_TRUE(file.commit().ok());
    EXPECT_TRUE(isLink(path("link1.ams")) && isLink(path("link2.ams"))) << link;
    EXPECT_EQ(contents(path("real/out.ams")), link);
    EXPECT_EQ(names(path("real")), std::vector<std::string>{"out.ams"});
  }
  EXPECT_EQ(names(dir), top);
}

TEST_F(AtomicFileTest, ASymbolicLinkStaysALinkAndItsTargetIsReplaced) {
  checkLinksStayLinks(dir_ / "unnamed", true);
  NamedTemporaries named;
  checkLinksStayLinks(dir_ / "named", false);
}

TEST_F(AtomicFileTest, ADanglingLinkCreatesItsTargetAndALoopIsRefused) {
  fs::create_directories(path("real"));
  fs::create_symlink("real/new.ams", path("dangling.ams"));
  AtomicFile file;
  ASSERT_TRUE(file.open(path("dangling.ams")).ok());
  ASSERT_TRUE(file.write("new", 3).ok());
  ASSERT_TRUE(file.commit().ok());
  EXPECT_TRUE(isLink(path("dangling.ams")));
  EXPECT_EQ(contents(path("real/new.ams")), "new");

  fs::create_symlink("loop_b", path("loop_a"));
  fs::create_symlink("loop_a", path("loop_b"));
  Status s = file.open(path("loop_a"));
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find("too many levels of symbolic links"), std::string::npos) << s.message();
  EXPECT_TRUE(isLink(path("loop_a")) && isLink(path("loop_b")));
  EXPECT_EQ(names(dir_), (std::vector<std::string>{"dangling.ams", "loop_a", "loop_b", "real"}));
}

}  // namespace
}  // namespace animc
