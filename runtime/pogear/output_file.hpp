// Writing an output file so that no failure, interrupt or concurrent run can leave a half-written
// file where a good one was, replace something that is not a regular file, or write through a link.
#pragma once

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pogear::rt {

// What stands at an output path decides how it is written:
//   nothing, or a regular file: the contents go to a new file in the same directory that nobody
//     else can open by name (O_TMPFILE; a file of a name mkstemp made unique where the file system
//     has no O_TMPFILE), which replaces the target by rename(2) once complete: readers and
//     concurrent runs see the old file or the new one, never a mix; a crash before the commit leaves
//     the target as it was (and with O_TMPFILE not even a temporary file);
//   a character device or a FIFO (/dev/null, a pipe a user reads from): written in place, as a
//     shell redirection would; replacing it would break the system or the reader;
//   a symbolic link: refused; writing through it would change a file elsewhere, replacing it would
//     silently drop the link, and neither is what the user named;
//   anything else (a directory, a socket, a block device): refused.
class OutputFile {
 public:
  // Opens PATH for writing; on failure ok() is false and error() says why in a sentence that ends
  // with what to do.
  explicit OutputFile(std::string path) : path_(std::move(path)) { open(); }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile() { abandon(); }

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  const std::string& path() const { return path_; }
  // The name of the temporary file while one exists by name (mkstemp fallback), for clean-up on
  // interrupts; empty with O_TMPFILE, whose file has no name until it is complete.
  const std::string& temporary_name() const { return temp_name_; }

  bool write(std::string_view data) {
    if (fd_ < 0 || !ok()) return false;
    while (!data.empty()) {
      const ssize_t n = ::write(fd_, data.data(), data.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return fail_errno("cannot write", "check the free space and the output directory");
      data.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
  }

  // Makes the written contents the file at PATH. After a failure PATH is as it was before.
  bool commit() {
    if (fd_ < 0 || !ok()) return false;
    if (in_place_) {
      const bool closed = ::close(fd_) == 0;
      fd_ = -1;
      return closed || fail_errno("cannot write", "check the output device");
    }
    // From the link to the rename the file has a name only this object knows: a signal there
    // would leave it behind, so signals wait until the rename is done (SIGKILL cannot wait).
    const BlockSignals quiet;
    if (temp_name_.empty() && !link_unnamed()) return false;
    const int closed = ::close(fd_);
    fd_ = -1;
    if (closed != 0) return fail_errno("cannot write", "check the free space and the output directory");
    if (::rename(temp_name_.c_str(), path_.c_str()) != 0)
      return fail_errno("cannot replace", "check the permissions of the output directory");
    temp_name_.clear();
    return true;
  }

  // Drops what was written: PATH stays as it was. Idempotent.
  void abandon() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!temp_name_.empty()) ::unlink(temp_name_.c_str());
    temp_name_.clear();
  }

 private:
  struct BlockSignals {
    sigset_t old;
    BlockSignals() {
      sigset_t all;
      sigfillset(&all);
      ::pthread_sigmask(SIG_BLOCK, &all, &old);
    }
    ~BlockSignals() { ::pthread_sigmask(SIG_SETMASK, &old, nullptr); }
    BlockSignals(const BlockSignals&) = delete;
    BlockSignals& operator=(const BlockSignals&) = delete;
  };

  bool fail(std::string message) {
    if (error_.empty()) error_ = std::move(message);
    abandon();
    return false;
  }
  bool fail_errno(const char* what, const char* advice) {
    const int e = errno;
    return fail(std::string(what) + " " + path_ + ": " + std::strerror(e) + "; " + advice);
  }

  std::string directory() const {
    const auto slash = path_.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path_.substr(0, slash);
  }
  std::string base_name() const {
    const auto slash = path_.find_last_of('/');
    return slash == std::string::npos ? path_ : path_.substr(slash + 1);
  }

  void open() {
    const std::string name = base_name();
    if (path_.empty() || name.empty() || name == "." || name == "..") {
      fail("the output path '" + path_ + "' names no file; give a file name");
      return;
    }
    if (path_.find('\0') != std::string::npos) {
      fail("the output path contains a NUL character; give a file name");
      return;
    }
    struct stat st {};
    if (::lstat(path_.c_str(), &st) == 0) {
      if (S_ISLNK(st.st_mode)) {
        fail(path_ + " is a symbolic link; pogear does not write through links: give the link's target or "
                     "remove the link");
        return;
      }
      if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
        open_in_place();
        return;
      }
      if (!S_ISREG(st.st_mode)) {
        fail(path_ + (S_ISDIR(st.st_mode) ? " is a directory" : " is not a regular file") +
             "; give the path of a file to write");
        return;
      }
    } else if (errno != ENOENT) {
      fail_errno("cannot write", "check the path");
      return;
    }
    open_temporary();
  }

  void open_in_place() {
    // O_NONBLOCK: a FIFO nobody reads is an error (ENXIO), not a hang; then back to blocking writes.
    fd_ = ::open(path_.c_str(), O_WRONLY | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
    if (fd_ < 0) {
      if (errno == ENXIO) fail(path_ + " is a FIFO that nobody reads; start its reader first");
      else fail_errno("cannot write", "check the device");
      return;
    }
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !(S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))) {
      fail(path_ + " changed while it was opened; run again");
      return;
    }
    const int flags = ::fcntl(fd_, F_GETFL);
    if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
    in_place_ = true;
  }

  void open_temporary() {
    const std::string dir = directory();
    // Regular files get the permissions a plain creation would give them (0666 less the umask).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    const mode_t mode = 0666 & ~mask;
#if defined(O_TMPFILE)
    fd_ = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, mode);
    if (fd_ >= 0) return;
    if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) {
      fail_errno("cannot write", "check that the output directory exists and is writable");
      return;
    }
#endif
    std::string tmpl = dir + "/." + base_name() + ".tmpXXXXXX";
    fd_ = ::mkostemp(tmpl.data(), O_CLOEXEC);
    if (fd_ < 0) {
      fail_errno("cannot write", "check that the output directory exists and is writable");
      return;
    }
    temp_name_ = tmpl;
    ::fchmod(fd_, mode);
  }

  // Gives the unnamed O_TMPFILE file a name that no other file has (a link to an existing name
  // fails, so nothing is replaced by accident), for the rename over the target.
  bool link_unnamed() {
    const std::string proc = "/proc/self/fd/" + std::to_string(fd_);
    const std::string dir = directory();
    for (int attempt = 0; attempt < 100; ++attempt) {
      std::string name = dir + "/." + base_name() + ".tmp" + std::to_string(::getpid()) + "_" +
                         std::to_string(attempt);
      if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) {
        temp_name_ = std::move(name);
        return true;
      }
      if (errno != EEXIST) break;
    }
    return fail_errno("cannot write", "check that /proc is mounted and the output directory is writable");
  }

  std::string path_, error_, temp_name_;
  int fd_ = -1;
  bool in_place_ = false;
};

}  // namespace pogear::rt
