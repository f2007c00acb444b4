#include "core/atomic_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <system_error>

namespace lumis {

namespace {

/// The system's words for an errno value (thread-safe, unlike strerror).
std::string reason(int error) { return std::generic_category().message(error); }

/// Writes all of `bytes` to `fd`, resuming after signals and short writes; "" or why not.
std::string write_all(int fd, std::string_view bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const size_t chunk = std::min<size_t>(bytes.size() - done, size_t{1} << 30);
    const ssize_t n = ::write(fd, bytes.data() + done, chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n < 0 ? reason(errno) : "the system accepted no more bytes";
      return "cannot write: " + why + " (after " + std::to_string(done) + " of " + std::to_string(bytes.size()) +
             " bytes)";
    }
    done += static_cast<size_t>(n);
  }
  return {};
}

// The temporary files being written, for a signal that would end the process mid-write: SIGINT (Ctrl-C), SIGTERM,
// SIGHUP (a closed terminal) and SIGQUIT, where the command leaves them to their default action, remove them first.
// A few slots, for writes on several threads at once; a longer path, or a ninth write, goes unguarded.
constexpr int kSlots = 8;
constexpr size_t kPathMax = 4096;
char g_tmp_path[kSlots][kPathMax];
std::atomic<bool> g_tmp_used[kSlots];
constexpr int kEndingSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
std::mutex g_handlers_mutex;
int g_writers = 0;  // writes in progress; the handlers are installed while there are any
bool g_installed[std::size(kEndingSignals)];

void remove_temporaries_and_end(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (g_tmp_used[i].load()) ::unlink(g_tmp_path[i]);  // async-signal-safe
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig);  // the default action, so the exit status is the signal's (130 for Ctrl-C)
}

/// Registers `tmp` for removal by the handlers while it lives; installs them for the signals still at their default
/// action (a command that handles one itself, as render does Ctrl-C, keeps its handler).
class TemporaryGuard {
 public:
  explicit TemporaryGuard(const std::string& tmp) {
    if (tmp.size() < kPathMax)
      for (int i = 0; i < kSlots && slot_ < 0; ++i) {
        bool expected = false;
        if (!g_tmp_used[i].load() && g_tmp_used[i].compare_exchange_strong(expected, true)) slot_ = i;
      }
    if (slot_ >= 0) {
      g_tmp_used[slot_].store(false);  // written while unused: the handler never reads a half-copied path
      std::memcpy(g_tmp_path[slot_], tmp.c_str(), tmp.size() + 1);
      g_tmp_used[slot_].store(true);
    }
    const std::lock_guard<std::mutex> lock(g_handlers_mutex);
    if (g_writers++ > 0) return;
    for (size_t k = 0; k < std::size(kEndingSignals); ++k) {
      struct sigaction old {};
      g_installed[k] = false;
      if (::sigaction(kEndingSignals[k], nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
      struct sigaction act {};
      act.sa_handler = remove_temporaries_and_end;
      sigfillset(&act.sa_mask);
      g_installed[k] = ::sigaction(kEndingSignals[k], &act, nullptr) == 0;
    }
  }
  ~TemporaryGuard() {
    {
      const std::lock_guard<std::mutex> lock(g_handlers_mutex);
      if (--g_writers == 0)
        for (size_t k = 0; k < std::size(kEndingSignals); ++k)
          if (g_installed[k]) {
            struct sigaction dfl {};
            dfl.sa_handler = SIG_DFL;
            ::sigaction(kEndingSignals[k], &dfl, nullptr);
          }
    }
    if (slot_ >= 0) g_tmp_used[slot_].store(false);
  }
  TemporaryGuard(const TemporaryGuard&) = delete;
  TemporaryGuard& operator=(const TemporaryGuard&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace

// The temporary file beside `path`: `path.tmp-<pid>`, or where that name would pass the longest name its folder's
// file system allows (255 bytes on Linux's), `path`'s name cut short to fit, with a count of such names (one
// process may write two long names that share their first 240 bytes at once).
std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned> count{0};
  const size_t slash = path.rfind('/');
  const std::string folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string name = path.substr(folder.size());
  const std::string suffix = ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  long limit = ::pathconf(folder.empty() ? "." : folder.c_str(), _PC_NAME_MAX);
  if (limit <= 0) limit = 255;  // no limit known: Linux's
  if (name.size() + suffix.size() <= static_cast<size_t>(limit)) return path + suffix;
  const std::string unique = suffix + "-" + std::to_string(count++);
  size_t keep = static_cast<size_t>(limit) - std::min(unique.size(), static_cast<size_t>(limit));
  while (keep > 0 && (static_cast<unsigned char>(name[keep]) & 0xC0) == 0x80) --keep;  // not inside a UTF-8 character
  return folder + name.substr(0, keep) + unique;
}

std::string written_file(const std::string& path, bool* loop) {
  std::string p = path;
  if (loop) *loop = false;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::string target(4096, '\0');
    const ssize_t n = ::readlink(p.c_str(), target.data(), target.size());
    if (n <= 0 || static_cast<size_t>(n) >= target.size()) return p;  // unreadable: let the write say why
    target.resize(static_cast<size_t>(n));
    const size_t slash = p.rfind('/');
    p = target.front() == '/' || slash == std::string::npos ? target : p.substr(0, slash + 1) + target;
  }
  if (loop) *loop = true;
  return p;
}

std::string write_file_atomically(const std::string& link_or_path, std::string_view bytes) {
  bool loop = false;
  const std::string path = written_file(link_or_path, &loop);
  if (loop) return "cannot create the file: " + reason(ELOOP);
  // Through a link, the reason names the file actually written.
  const std::string via = path == link_or_path ? "" : " (writing " + path + ", where the link leads)";
  // A pipe, device or socket would be replaced by the rename, and a folder cannot be (the commands refuse both up
  // front; this is the last word, before anything is written).
  struct stat old {};
  const bool exists = ::stat(path.c_str(), &old) == 0;
  if (exists && S_ISDIR(old.st_mode)) return "cannot replace it: it is a folder" + via;
  if (exists && !S_ISREG(old.st_mode))
    return "cannot replace it: not a regular file (a pipe, device or socket)" + via;
  std::string why;
  const std::string tmp = temporary_name(path);
  const TemporaryGuard guard(tmp);  // registered before it exists: a signal after open() still removes it
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return "cannot create the file: " + reason(errno) + via;
  // A file replaced keeps its permissions (a private 0600 image stays private); a new one gets 0666 less the umask.
  if (exists) ::fchmod(fd, old.st_mode & 0777);
  why = write_all(fd, bytes);
  // close() reports what a network or quota-limited file system only learns when the data leaves the cache. On
  // Linux the descriptor is released even when close fails, so it is never retried.
  if (::close(fd) != 0 && why.empty()) why = "cannot write: " + reason(errno) + " (when closing the file)";
  if (why.empty() && std::rename(tmp.c_str(), path.c_str()) != 0)
    why = "cannot rename the finished temporary file into place: " + reason(errno);
  if (!why.empty()) ::unlink(tmp.c_str());
  return why.empty() ? why : why + via;
}

}  // namespace lumis
