// A full disk without one: a file-size limit (RLIMIT_FSIZE, as `ulimit -f` sets) makes every write past it fail
// (EFBIG, "File too large") the way a full disk fails them (ENOSPC), in any folder and without privileges.
#pragma once

#include <sys/resource.h>

#include <csignal>

namespace lumis::test {

/// Limits the size of files this process writes to `bytes` until destroyed. SIGXFSZ is ignored meanwhile, as lumis's
/// main() ignores it: its default action would kill the test instead of failing the write.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    ok_ = ::setrlimit(RLIMIT_FSIZE, &limit) == 0;
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;
  /// False when the limit could not be set (a hard limit below `bytes`): the test cannot run.
  bool ok() const { return ok_; }

 private:
  rlimit saved_{};
  void (*handler_)(int) = SIG_DFL;
  bool ok_ = false;
};

}  // namespace lumis::test
