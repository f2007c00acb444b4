// write_file_atomically: a file is written whole or not at all, and a failure says why without naming the
// temporary file. A file-size limit stands in for a full disk (tests/support/file_size_limit.h).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/atomic_write.h"
#include "tests/support/file_size_limit.h"
#include "tests/support/test_dir.h"

namespace fs = std::filesystem;
using namespace lumis;

namespace {

class AtomicWrite : public test::FolderTest {
 protected:
  AtomicWrite() : FolderTest("lumis_atomic_write") {}
  std::string content(const std::string& name) const {
    std::ifstream in(file(name), std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
};

}  // namespace

TEST_F(AtomicWrite, WritesWholeFilesAndReplacesOldOnes) {
  EXPECT_EQ(write_file_atomically(file("a.txt"), "first"), "");
  EXPECT_EQ(content("a.txt"), "first");
  const std::string big(300000, 'x');
  EXPECT_EQ(write_file_atomically(file("a.txt"), big), "");
  EXPECT_EQ(content("a.txt"), big);
  EXPECT_EQ(write_file_atomically(file("empty.txt"), ""), "");
  EXPECT_TRUE(fs::exists(file("empty.txt")));
  EXPECT_EQ(fs::file_size(file("empty.txt")), 0u);
  EXPECT_EQ(listing().size(), 2u);
}

// A path that is a symbolic link (-o latest.png -> renders/0042.png) is written through, as a shell's `>` does: the
// link stays a link and its target gets the bytes. Renaming over the link replaced it with a file and left the
// target stale. Relative links are read from the link's folder; a chain is followed; a dangling link creates its
// target; a loop of links is an error.
TEST_F(AtomicWrite, ASymbolicLinkIsWrittenThrough) {
  fs::create_directories(file("renders"));
  ASSERT_EQ(write_file_atomically(file("renders/0042.png"), "old"), "");
  fs::create_symlink("renders/0042.png", file("latest.png"));
  EXPECT_EQ(write_file_atomically(file("latest.png"), "new"), "");
  EXPECT_TRUE(fs::is_symlink(file("latest.png")));
  EXPECT_EQ(content("renders/0042.png"), "new");
  fs::create_symlink(file("latest.png"), file("chain.png"));  // absolute, to a link
  EXPECT_EQ(write_file_atomically(file("chain.png"), "newer"), "");
  EXPECT_TRUE(fs::is_symlink(file("chain.png")));
  EXPECT_EQ(content("renders/0042.png"), "newer");
  fs::create_symlink("renders/0043.png", file("next.png"));  // dangling
  EXPECT_EQ(write_file_atomically(file("next.png"), "first"), "");
  EXPECT_EQ(content("renders/0043.png"), "first");
  EXPECT_EQ(written_file(file("chain.png")), file("renders/0042.png"));  // the path the checks look at
  EXPECT_EQ(written_file(file("renders/0042.png")), file("renders/0042.png"));
  fs::create_symlink("loop-b", file("loop-a"));
  fs::create_symlink("loop-a", file("loop-b"));
  bool loop = false;
  written_file(file("loop-a"), &loop);
  EXPECT_TRUE(loop);
  EXPECT_NE(write_file_atomically(file("loop-a"), "x"), "");
  // A link into a missing folder: the reason names where the link leads.
  fs::create_symlink("nowhere/x.png", file("lost.png"));
  EXPECT_NE(write_file_atomically(file("lost.png"), "x").find("(writing " + file("nowhere/x.png") + ", where the link "
                                                                "leads)"),
            std::string::npos);
  for (const auto& e : fs::directory_iterator(file("renders")))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

// The case that made this function: a write cut short (full disk, file-size limit) must not leave a short file
// under the name asked for, and must say how far it got.
TEST_F(AtomicWrite, AWriteCutShortKeepsTheOldFileAndLeavesNoTemporary) {
  ASSERT_EQ(write_file_atomically(file("keep.bin"), "old content"), "");
  const std::string bytes(100000, 'y');
  std::string why;
  {
    test::FileSizeLimit limit(4096);
    if (!limit.ok()) GTEST_SKIP() << "cannot set a file-size limit here";
    why = write_file_atomically(file("keep.bin"), bytes);
    // A new name fails alike and leaves nothing.
    EXPECT_EQ(write_file_atomically(file("new.bin"), bytes), why);
  }
  EXPECT_EQ(why, "cannot write: File too large (after 4096 of 100000 bytes)");
  EXPECT_EQ(content("keep.bin"), "old content");
  EXPECT_EQ(listing(), std::vector<std::string>{"keep.bin"});
}

TEST_F(AtomicWrite, AMissingFolderOrAFolderInTheWayIsAnErrorNamingNoTemporary) {
  EXPECT_EQ(write_file_atomically(file("no-such-folder/a.txt"), "x"),
            "cannot create the file: No such file or directory");
  fs::create_directories(dir_ / "taken" / "inside");
  const std::string why = write_file_atomically(file("taken"), "x");
  EXPECT_EQ(why, "cannot replace it: it is a folder");  // refused before a temporary is written
  EXPECT_EQ(why.find("tmp-"), std::string::npos) << why;
  EXPECT_EQ(listing(), std::vector<std::string>{"taken"});
}

// A name the file system takes (up to 255 bytes on Linux) is written, though NAME.tmp-PID would be too long: the
// temporary name is cut short. Once a 248-byte name failed with "File name too long", after the whole render.
TEST_F(AtomicWrite, TheLongestNameTheFileSystemAllowsIsWritten) {
  const long limit = ::pathconf(dir_.c_str(), _PC_NAME_MAX);
  ASSERT_GT(limit, 16);
  const std::string longest(static_cast<size_t>(limit) - 4, 'a'), other = longest.substr(0, longest.size() - 1) + "b";
  EXPECT_EQ(write_file_atomically(file(longest + ".png"), "one"), "");
  EXPECT_EQ(write_file_atomically(file(other + ".png"), "two"), "");
  EXPECT_EQ(content(longest + ".png"), "one");
  EXPECT_EQ(content(other + ".png"), "two");
  EXPECT_EQ(listing(), (std::vector<std::string>{longest + ".png", other + ".png"}));
  EXPECT_NE(write_file_atomically(file(longest + "x.png"), "x").find("File name too long"), std::string::npos);
  EXPECT_EQ(listing().size(), 2u);
  // A name of three-byte characters is cut at a character's start, not inside one (a leftover of a killed run
  // would otherwise carry a name that is not UTF-8). After 0, 1 and 2 ASCII letters: at least two cut mid-character.
  for (const std::string lead : {"", "a", "aa"}) {
    std::string euros = lead;
    while (euros.size() + 3 + 4 <= static_cast<size_t>(limit)) euros += "\xE2\x82\xAC";
    const std::string tmp = fs::path(temporary_name(file(euros + ".png"))).filename().string();
    EXPECT_LE(tmp.size(), static_cast<size_t>(limit));
    const size_t cut = tmp.find(".tmp-");
    ASSERT_NE(cut, std::string::npos);
    EXPECT_EQ((cut - lead.size()) % 3, 0u) << tmp;  // whole euro signs before the suffix
    EXPECT_EQ(write_file_atomically(file(euros + ".png"), "euro"), "");
    EXPECT_EQ(content(euros + ".png"), "euro");
  }
}

// A run killed mid-write (SIGKILL, power loss) leaves its temporary file; a later process may get the same pid and so
// the same temporary name. Its write must replace the leftover whole, not overwrite its start and keep its tail.
TEST_F(AtomicWrite, ALongerLeftoverTemporaryDoesNotKeepItsTail) {
  const std::string leftover = file("out.txt") + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  std::ofstream(leftover, std::ios::binary) << std::string(1000, 'z');
  EXPECT_EQ(write_file_atomically(file("out.txt"), "short"), "");
  EXPECT_EQ(content("out.txt"), "short");
  EXPECT_EQ(listing(), std::vector<std::string>{"out.txt"});
}

// A pipe, device or socket where the file should go is not replaced by a file (the rename would have done so: as
// root, `bench --json /dev/null` replaced /dev/null). The write is refused and the pipe stays.
TEST_F(AtomicWrite, APipeOrDeviceIsNotReplaced) {
  ASSERT_EQ(::mkfifo(file("fifo").c_str(), 0600), 0);
  const std::string why = write_file_atomically(file("fifo"), "bytes");
  EXPECT_NE(why.find("not a regular file"), std::string::npos) << why;
  EXPECT_TRUE(fs::is_fifo(file("fifo")));
  EXPECT_EQ(listing().size(), 1u);  // no temporary left
}

// A file replaced keeps its permissions: a private (0600) image stays private, a read-only one read-only.
TEST_F(AtomicWrite, AReplacedFileKeepsItsPermissions) {
  for (const mode_t mode : {mode_t{0600}, mode_t{0444}, mode_t{0640}}) {
    ASSERT_EQ(write_file_atomically(file("p.txt"), "old"), "");
    ASSERT_EQ(::chmod(file("p.txt").c_str(), mode), 0);
    ASSERT_EQ(write_file_atomically(file("p.txt"), "new"), "");
    struct stat st {};
    ASSERT_EQ(::stat(file("p.txt").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, mode) << std::oct << mode;
    EXPECT_EQ(content("p.txt"), "new");
    ::chmod(file("p.txt").c_str(), 0600);
    fs::remove(file("p.txt"));
  }
}

// A signal that ends the process during the write (Ctrl-C in diff or compare, SIGHUP when the terminal closes) first
// removes the temporary file. Deterministic: the temporary's name is made a FIFO before the child writes, so the
// child blocks in open() with its temporary registered, and is sent the signal there; it must die of it having
// removed the FIFO. (Without the handler the FIFO stays, as a half-written image did.) The child says when it starts
// the write, and after that open() is the only place it can sleep, so the parent waits for both.
TEST_F(AtomicWrite, ASignalDuringTheWriteRemovesTheTemporary) {
  for (const int sig : {SIGTERM, SIGINT, SIGHUP}) {
    int go[2], started[2];
    ASSERT_EQ(::pipe(go), 0);
    ASSERT_EQ(::pipe(started), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::signal(sig, SIG_DFL);
      char c;
      if (::read(go[0], &c, 1) != 1 || ::write(started[1], "s", 1) != 1) ::_exit(3);
      write_file_atomically(file("out.png"), "bytes");
      ::_exit(4);  // the write finished: the FIFO never blocked it
    }
    ::close(go[0]);
    ::close(started[1]);
    const std::string tmp = file("out.png") + ".tmp-" + std::to_string(child);
    ASSERT_EQ(::mkfifo(tmp.c_str(), 0600), 0);
    ASSERT_EQ(::write(go[1], "x", 1), 1);
    ::close(go[1]);
    char c;
    ASSERT_EQ(::read(started[0], &c, 1), 1);  // the child is past its read, on its way into the write
    ::close(started[0]);
    // It sleeps only in open() now: poll its state in /proc until it does (at most 10 s).
    bool blocked = false;
    for (int i = 0; i < 10000 && !blocked; ++i) {
      std::ifstream stat("/proc/" + std::to_string(child) + "/stat");
      std::string pid, comm, state;
      stat >> pid >> comm >> state;
      blocked = state == "S";
      if (!blocked) ::usleep(1000);
    }
    ::kill(child, sig);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "signal " << sig << ", status " << status;
    EXPECT_FALSE(fs::exists(fs::symlink_status(tmp))) << "signal " << sig << ": the temporary is still there";
    EXPECT_FALSE(fs::exists(file("out.png")));
    fs::remove(tmp);
  }
}
