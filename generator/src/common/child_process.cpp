// Children are started with fork and exec rather than std::system, so that arguments need no
// quoting, their process group and death signal can be set, and their input and output go through pipes.
#include "common/child_process.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <exception>
#include <stdexcept>
#include <string_view>
#include <tuple>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "common/interrupts.hpp"

namespace pogear {
namespace {

struct Fd {
  int fd = -1;
  Fd() = default;
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  void reset() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

void make_pipe(Fd& read_end, Fd& write_end) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(fmt::format("cannot create a pipe: {}", std::strerror(errno)));
  read_end.fd = fds[0];
  write_end.fd = fds[1];
}

// Feeds the child's standard input and reads its outputs at once, through pipes: a child that
// writes before it has read all its input (or a lot) never waits on pogear. Pipes, unlike files,
// are not bound by the file size limit, so `ulimit -f` reaches only what pogear writes to disk.
void exchange(Fd& to_child, std::string_view input, Fd& from_out, std::string& out, Fd& from_err, std::string& err) {
  if (to_child.fd >= 0) ::fcntl(to_child.fd, F_SETFL, ::fcntl(to_child.fd, F_GETFL) | O_NONBLOCK);
  if (to_child.fd >= 0 && input.empty()) to_child.reset();
  char chunk[1 << 16];
  while (to_child.fd >= 0 || from_out.fd >= 0 || from_err.fd >= 0) {
    pollfd fds[3] = {{to_child.fd, POLLOUT, 0}, {from_out.fd, POLLIN, 0}, {from_err.fd, POLLIN, 0}};
    if (::poll(fds, 3, -1) < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("cannot wait for a child's output: {}", std::strerror(errno)));
    }
    if (to_child.fd >= 0 && (fds[0].revents & (POLLOUT | POLLERR | POLLHUP))) {
      const ssize_t n = ::write(to_child.fd, input.data(), input.size());
      if (n > 0) input.remove_prefix(static_cast<std::size_t>(n));
      if ((n < 0 && errno != EAGAIN && errno != EINTR) || input.empty()) to_child.reset();  // EPIPE: it stopped reading
    }
    for (auto [fd, text, revents] : {std::tuple<Fd*, std::string*, short>{&from_out, &out, fds[1].revents},
                                     std::tuple<Fd*, std::string*, short>{&from_err, &err, fds[2].revents}}) {
      if (fd->fd < 0 || !(revents & (POLLIN | POLLERR | POLLHUP))) continue;
      const ssize_t n = ::read(fd->fd, chunk, sizeof chunk);
      if (n > 0) text->append(chunk, static_cast<std::size_t>(n));
      else if (n == 0 || (errno != EINTR && errno != EAGAIN)) fd->reset();
    }
  }
}

}  // namespace

std::string ChildResult::describe() const {
  if (signal == 0) return fmt::format("exit status {}", exit_code);
  const char* name = ::strsignal(signal);
  return fmt::format("signal {} ({})", signal, name ? name : "unknown");
}

std::optional<std::string> find_program(const std::string& name) {
  if (name.empty()) return std::nullopt;
  if (name.find('/') != std::string::npos)
    return ::access(name.c_str(), X_OK) == 0 ? std::optional<std::string>(name) : std::nullopt;
  const char* path = std::getenv("PATH");
  std::string dirs = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    const std::string candidate = dir + "/" + name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
    start = end + 1;
  }
  return std::nullopt;
}

ChildResult run_child(const ChildRequest& request) {
  if (request.argv.empty()) throw std::runtime_error("no program to run");
  const std::optional<std::string> program = find_program(request.argv[0]);
  if (!program) throw std::runtime_error(fmt::format("cannot run {}: not found or not executable", request.argv[0]));

  // Pipe ends: the child's (c_) are dup'ed to 0, 1, 2 and closed in pogear after fork.
  Fd c_in, p_in, p_out, c_out, p_err, c_err;
  if (request.input) make_pipe(c_in, p_in);
  else c_in.fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (request.capture_stdout) make_pipe(p_out, c_out);
  if (request.capture_stderr && !request.stderr_to_stdout) make_pipe(p_err, c_err);

  // Everything the child needs, built before fork: between fork and exec only system calls.
  std::vector<char*> argv;
  for (const auto& a : request.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int err_target = request.stderr_to_stdout ? c_out.fd : c_err.fd;

  // Signals wait until the child's group is known to the handler (ChildSession). SIGPIPE stays
  // blocked while pogear feeds the child: a child that stops reading is not pogear's death.
  sigset_t all, old;
  sigfillset(&all);
  ::pthread_sigmask(SIG_BLOCK, &all, &old);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(128 + SIGKILL);  // pogear already died
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old_action {};
      if (::sigaction(sig, nullptr, &old_action) == 0 && old_action.sa_handler != SIG_IGN) std::signal(sig, SIG_DFL);
    }
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    ::dup2(c_in.fd, 0);
    if (c_out.fd >= 0) ::dup2(c_out.fd, 1);
    if (err_target >= 0) ::dup2(err_target, 2);
    ::execv(program->c_str(), argv.data());
    ::_exit(127);
  }
  if (pid < 0) {
    const int e = errno;
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    throw std::runtime_error(fmt::format("cannot start {}: {}", request.argv[0], std::strerror(e)));
  }
  ::setpgid(pid, pid);  // also here, so that the group exists before a signal is passed on
  ChildSession session(pid);
  sigset_t pipe_only = old;
  sigaddset(&pipe_only, SIGPIPE);
  ::pthread_sigmask(SIG_SETMASK, &pipe_only, nullptr);
  c_in.reset();
  c_out.reset();
  c_err.reset();

  ChildResult result;
  std::exception_ptr failure;
  try {
    exchange(p_in, request.input ? std::string_view(*request.input) : std::string_view(), p_out, result.out, p_err,
             result.err);
  } catch (...) {
    failure = std::current_exception();
    ::kill(-pid, SIGKILL);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  // A SIGPIPE from a child that stopped reading is consumed here, then the mask is as it was.
  const timespec no_wait{0, 0};
  sigset_t pipe_set;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  while (::sigtimedwait(&pipe_set, nullptr, &no_wait) == SIGPIPE) {
  }
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  session.child_ended();  // dies here if pogear was interrupted meanwhile
  if (failure) std::rethrow_exception(failure);

  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  else result.exit_code = WEXITSTATUS(status);
  return result;
}

}  // namespace pogear
