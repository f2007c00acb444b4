#include "core/atomic_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
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

}  // namespace

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
  std::string why;
  const std::string tmp = path + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return "cannot create the file: " + reason(errno) + via;
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
