// Malformed input never crashes lumis (docs/robustness.md). Every case in tests/malformed/ (an input NAME.EXT beside
// NAME.expect, see tests/malformed/make_cases.py) goes through the whole command line in this process,
//   lumis render NAME.EXT -o out.png --spp 1 --width 8 --height 8 -q [the .expect's args]
// and must return the expected exit code (`exit:`, 1 when absent; 2 for usage errors), print the expected substring
// (`stderr:`) on stderr, and leave no file in the output folder; a case expecting 0 must write the image instead.
// A crash or a sanitizer report fails the run. In-process, because starting lumis costs about 0.5 s of dynamic
// linking (OpenImageIO's 260 libraries) per case; the cases that need a process and a file system object of their
// own (a missing file, a folder, a pipe, an unreadable file) are in tests/cli/malformed.sh.
// One case: test_malformed --gtest_filter='*/glb_bad_magic'
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli.h"

namespace fs = std::filesystem;

namespace {

struct Case {
  std::string name;
  fs::path input;
  int exit_code = 1;
  std::string stderr_has;
  std::vector<std::string> args;
};

/// gtest names a failing case by its parameter: the case's name, not its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

fs::path cases_dir() { return fs::path(LUMIS_SOURCE_DIR) / "tests" / "malformed"; }

/// The value of `key: value` in an .expect file ("" when absent, or for `key:` alone).
std::string field(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key + ":", 0) != 0) continue;
    std::string value = line.substr(key.size() + 1);
    return value.empty() || value[0] != ' ' ? value : value.substr(1);
  }
  return "";
}

/// Every NAME.expect with its input file, sorted by name. A case without an input file keeps an empty `input`
/// and fails below.
std::vector<Case> load_cases() {
  std::vector<Case> cases;
  for (const auto& entry : fs::directory_iterator(cases_dir())) {
    if (entry.path().extension() != ".expect") continue;
    Case c;
    c.name = entry.path().stem().string();
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (const std::string code = field(text, "exit"); !code.empty()) c.exit_code = std::stoi(code);
    c.stderr_has = field(text, "stderr");
    std::istringstream args(field(text, "args"));
    for (std::string a; args >> a;) c.args.push_back(a);
    for (const auto& other : fs::directory_iterator(cases_dir()))
      if (other.path().stem() == c.name && other.path().extension() != ".expect") c.input = other.path();
    cases.push_back(c);
  }
  std::sort(cases.begin(), cases.end(), [](const Case& a, const Case& b) { return a.name < b.name; });
  return cases;
}

/// Runs lumis's command line with file descriptor 2 sent to `err_file`; returns its exit code.
int run_lumis(std::vector<std::string> args, const fs::path& err_file) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  std::cerr.flush();
  std::fflush(stderr);
  const int saved = ::dup(2);
  std::FILE* err = std::fopen(err_file.c_str(), "w");
  ::dup2(::fileno(err), 2);
  const int code = lumis::run_cli(static_cast<int>(argv.size()), argv.data());
  std::cerr.flush();
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::fclose(err);
  return code;
}

class Malformed : public ::testing::TestWithParam<Case> {};

TEST_P(Malformed, ExitsWithTheExpectedCodeAndMessageAndNoOutput) {
  const Case& c = GetParam();
  ASSERT_FALSE(c.input.empty()) << c.name << ".expect has no input file beside it";
  const fs::path dir = fs::temp_directory_path() / ("malformed_" + std::to_string(::getpid()) + "_" + c.name);
  fs::remove_all(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  std::vector<std::string> args = {"lumis", "render", c.input.string(), "-o", (out / "out.png").string(), "--spp",
                                   "1", "--width", "8", "--height", "8", "-q"};
  args.insert(args.end(), c.args.begin(), c.args.end());
  const int code = run_lumis(args, dir / "stderr.txt");
  std::ifstream in(dir / "stderr.txt");
  const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(code, c.exit_code) << "stderr: " << err;
  EXPECT_NE(err.find(c.stderr_has), std::string::npos) << "stderr lacks '" << c.stderr_has << "': " << err;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(out)) left.push_back(e.path().filename().string());
  if (c.exit_code == 0) {
    EXPECT_TRUE(fs::exists(out / "out.png") && fs::file_size(out / "out.png") > 0) << "no image written";
  } else {
    EXPECT_TRUE(left.empty()) << "left files, such as " << left.front();
    EXPECT_FALSE(err.empty()) << "no message on stderr";
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Cases, Malformed, ::testing::ValuesIn(load_cases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

// The case list is read from the folder, so a lost folder would pass as zero cases.
TEST(MalformedCases, AreFound) { EXPECT_GE(load_cases().size(), 100u); }

}  // namespace
