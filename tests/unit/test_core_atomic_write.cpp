// write_file_atomically: a file is written whole or not at all, and a failure says why without naming the
// temporary file. A file-size limit stands in for a full disk (tests/support/file_size_limit.h).
#include <gtest/gtest.h>
#include <unistd.h>

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
  EXPECT_EQ(why.rfind("cannot rename the finished temporary file into place: ", 0), 0u) << why;
  EXPECT_EQ(why.find("tmp-"), std::string::npos) << why;
  EXPECT_EQ(listing(), std::vector<std::string>{"taken"});
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
