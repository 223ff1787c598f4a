// Reading an input file (a model, a scene, a signal table) with bounded cost: only a regular
// file is read, and never more than a limit, whatever the path turns out to be.
#pragma once

#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pogear::rt {

enum class InputFileStatus { ok, cannot_open, directory, not_regular, too_large, read_error };

struct InputFile {
  InputFileStatus status = InputFileStatus::ok;
  std::string text;
  std::string reason;  // the system's reason (strerror), or the kind of file that is not regular
};

// What a file of mode `mode` is, for messages: "a FIFO", "a character device", ...
inline const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Reads up to `limit` + 1 bytes of `path` (one past the limit tells a file over it). The file is
// opened without blocking and its type checked on the open descriptor, so that a FIFO with no
// writer, a terminal or a device is refused at once instead of hanging or never ending, and a file
// swapped after a check cannot slip in. Symbolic links are followed: they name the file to read.
inline InputFile read_regular_file(const std::string& path, std::size_t limit) {
  InputFile in;
  auto fail = [&](InputFileStatus s, std::string reason) {
    in.status = s;
    in.reason = std::move(reason);
    in.text.clear();
    return in;
  };
  if (path.empty()) return fail(InputFileStatus::cannot_open, "the path is empty");
  if (path.find('\0') != std::string::npos) return fail(InputFileStatus::cannot_open, "the path contains a NUL character");
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return fail(InputFileStatus::cannot_open, std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return fail(InputFileStatus::read_error, std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return fail(InputFileStatus::directory, file_kind(st.st_mode));
  if (!S_ISREG(st.st_mode)) return fail(InputFileStatus::not_regular, file_kind(st.st_mode));
  char chunk[1 << 16];
  while (in.text.size() <= limit) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return fail(InputFileStatus::read_error, std::strerror(errno));
    if (n == 0) break;
    in.text.append(chunk, static_cast<std::size_t>(n));
  }
  if (in.text.size() > limit) return fail(InputFileStatus::too_large, "");
  return in;
}

}  // namespace pogear::rt
