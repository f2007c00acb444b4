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

/// The file a path names, following symbolic links (a relative link from the link's own folder), as `>` in a
/// shell does: renaming over the link itself would replace it with a file and leave its target as it was. *why is
/// set for a loop of links.
std::string follow_links(std::string path, std::string& why) {
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return path;
    std::string target(4096, '\0');
    const ssize_t n = ::readlink(path.c_str(), target.data(), target.size());
    if (n < 0 || static_cast<size_t>(n) >= target.size()) return path;  // unreadable: let the write say why
    target.resize(static_cast<size_t>(n));
    const size_t slash = path.rfind('/');
    path = target.front() == '/' || slash == std::string::npos ? target : path.substr(0, slash + 1) + target;
  }
  why = "cannot create the file: " + reason(ELOOP);
  return path;
}

}  // namespace

std::string write_file_atomically(const std::string& link_or_path, std::string_view bytes) {
  std::string why;
  const std::string path = follow_links(link_or_path, why);
  if (!why.empty()) return why;
  const std::string tmp = path + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return "cannot create the file: " + reason(errno);
  why = write_all(fd, bytes);
  // close() reports what a network or quota-limited file system only learns when the data leaves the cache. On
  // Linux the descriptor is released even when close fails, so it is never retried.
  if (::close(fd) != 0 && why.empty()) why = "cannot write: " + reason(errno) + " (when closing the file)";
  if (why.empty() && std::rename(tmp.c_str(), path.c_str()) != 0)
    why = "cannot rename the finished temporary file into place: " + reason(errno);
  if (!why.empty()) ::unlink(tmp.c_str());
  return why;
}

}  // namespace lumis
