#include "flexgait/core/atomic_file.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>  // renameat2 (glibc >= 2.28, _GNU_SOURCE)
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "flexgait/core/config.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait {
namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}

void write_all(int fd, std::string_view content, const std::filesystem::path& path) {
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write", path);
    }
    done += static_cast<std::size_t>(n);
  }
}

std::filesystem::path directory_of(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : ".";
}

// Makes a rename in `dir` durable (POSIX: the directory entry is on disk once the directory is fsync'ed).
void sync_directory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) fail("cannot open the directory", dir);
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  errno = err;
  if (rc != 0) fail("cannot flush the directory", dir);
}

// What a file of mode `mode` is, for messages ("" for a regular file).
std::string file_kind(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// The kind of `path` if it exists and is not a regular file or (`directory_ok`) a directory,
// links followed and named ("a symbolic link to a FIFO"); "" otherwise (absent, dangling link).
std::string unusable_kind(const std::filesystem::path& path, bool directory_ok) {
  struct stat target {};
  if (::stat(path.c_str(), &target) != 0) return "";  // absent (or a dangling link: replaced)
  if (S_ISREG(target.st_mode) || (directory_ok && S_ISDIR(target.st_mode))) return "";
  struct stat link {};
  const bool is_link = ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode);
  return (is_link ? "a symbolic link to " : "") + file_kind(target.st_mode);
}

std::string option_prefix(const std::string& option) {
  return option.empty() ? "output" : option;
}

}  // namespace

void check_output_file(const std::filesystem::path& path, const std::string& option) {
  if (path.empty())
    throw UsageError(
        fmt::format("{}: an empty path; allowed: a regular file (replaced whole) or a path that does not "
                    "exist yet",
                    option_prefix(option)));
  const std::string kind = unusable_kind(path, false);
  if (kind.empty()) return;
  throw UsageError(
      fmt::format("{}: {} is {}, not a regular file; allowed: a regular file (replaced whole) or a "
                  "path that does not exist yet",
                  option_prefix(option), one_line(path.string(), 1000), kind));
}

void check_output_directory(const std::filesystem::path& path, const std::string& option) {
  if (path.empty())
    throw UsageError(fmt::format("{}: an empty path; allowed: a directory or a path that does not exist yet",
                                 option_prefix(option)));
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;  // made later
  if (!S_ISDIR(st.st_mode))
    throw UsageError(
        fmt::format("{}: cannot make the run directory {}: it is {}, not a directory; allowed: a "
                    "directory or a path that does not exist yet",
                    option_prefix(option), one_line(path.string(), 1000),
                    S_ISREG(st.st_mode) ? "a regular file" : unusable_kind(path, false)));
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(path, ec)) {
    const std::string kind = unusable_kind(entry.path(), true);
    if (!kind.empty())
      throw UsageError(
          fmt::format("{}: cannot use the run directory {}: it holds {}, which is {}; allowed: a "
                      "directory of regular files and directories (remove it or choose another)",
                      option_prefix(option), one_line(path.string(), 1000),
                      one_line(entry.path().filename().string(), 1000), kind));
  }
}

// Linux's renameat2 creates the name only if it is absent (RENAME_NOREPLACE) or swaps the two
// names atomically (RENAME_EXCHANGE); after a swap the old target sits at `tmp`, is looked at,
// and is swapped back if it is a device, a FIFO, a socket or a directory, so such a file is never
// unlinked, whenever it appeared. Where the file system has no renameat2 (EINVAL, ENOSYS) the
// check and the rename are two calls. A target that keeps changing between the calls is tried 8
// times.
void rename_over_regular_file(const std::filesystem::path& tmp, const std::filesystem::path& target) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, target.c_str(), RENAME_NOREPLACE) == 0) return;
    if (errno == EINVAL || errno == ENOSYS) break;
    if (errno != EEXIST) fail("cannot rename into place", target);
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) != 0) {
      if (errno == ENOENT) continue;  // the target went away meanwhile: create it
      if (errno == EINVAL || errno == ENOSYS) break;
      fail("cannot rename into place", target);
    }
    const std::string kind = unusable_kind(tmp, false);  // the old target, now at tmp
    if (kind.empty()) {
      ::unlink(tmp.c_str());
      return;
    }
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) != 0)
      fail("cannot put back the file found at", target);
    check_output_file(target);  // throws, naming the kind
    break;                      // not reached: the file put back is the unusable one
  }
  check_output_file(target);
  if (::rename(tmp.c_str(), target.c_str()) != 0) fail("cannot rename into place", target);
}

void write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  AtomicFileWriter file(path);
  file.append(content);
  file.commit();
}

void write_file_durable(const std::filesystem::path& path, std::string_view content) {
  AtomicFileWriter file(path, Durability::Durable);
  file.append(content);
  file.commit();
}

AtomicFileWriter::AtomicFileWriter(std::filesystem::path path, Durability durability)
    : path_(std::move(path)), durability_(durability) {
  check_output_file(path_);
  const std::filesystem::path dir = directory_of(path_);
  std::string leaf = ".";  // built step by step: GCC 12 warns falsely (-Wrestrict) on a + b + c
  leaf += path_.filename().string();
  leaf += ".tmp-";
  leaf += std::to_string(::getpid());
  leaf += "-XXXXXX";
  const std::string pattern = (dir / leaf).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0) fail("cannot create a temporary file for", path_);
  tmp_ = name.data();
}

AtomicFileWriter::~AtomicFileWriter() {
  discard();
}

void AtomicFileWriter::discard() noexcept {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(tmp_.c_str());
  fd_ = -1;
}

void AtomicFileWriter::append(std::string_view content) {
  if (fd_ < 0) throw std::logic_error("AtomicFileWriter: append after commit");
  try {
    write_all(fd_, content, tmp_);
  } catch (...) {
    discard();
    throw;
  }
}

// Atomic writes rename without fsync: the rename alone makes the file whole-or-absent for every
// way a process can stop (the standard's "no half-written outputs"); an fsync adds survival of a
// power cut, and waits for the disk to do it. Measured on this machine's ext4 disk (/work) with
// the 6 files of `rimless simulate --steps 2000 --set sim.sample_dt=10` (5.8 MB, 10 runs each):
// rename only 1.4-1.6 ms; fsync before each rename 5.4-36 ms (15 ms median, more when other jobs
// write: whole runs took 0.26-0.62 s wall against 0.25-0.26 s on tmpfs); one syncfs at the end
// 4.6-25 ms (and it also waits for every other process's writes to that disk). Only files a
// resume trusts after a crash are durable (Durability::Durable, append_file_durable).
void AtomicFileWriter::commit() {
  if (fd_ < 0) throw std::logic_error("AtomicFileWriter: commit twice");
  const bool durable = durability_ == Durability::Durable;
  if (::fchmod(fd_, 0644) != 0 || (durable && ::fsync(fd_) != 0)) {
    const int err = errno;
    discard();
    errno = err;
    fail("cannot flush", tmp_);
  }
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    errno = err;
    fail("cannot close", tmp_);
  }
  try {
    rename_over_regular_file(tmp_, path_);
  } catch (...) {
    ::unlink(tmp_.c_str());
    throw;
  }
  if (durable) sync_directory(directory_of(path_));
}

long temporary_owner(const std::string& filename) {
  if (filename.empty() || filename[0] != '.') return 0;
  const std::size_t tag = filename.rfind(".tmp-");
  if (tag == std::string::npos) return 0;
  const std::size_t digits = tag + 5, dash = filename.find('-', digits);
  if (dash == std::string::npos || dash == digits || dash + 1 == filename.size() || dash - digits > 9) return 0;
  long pid = 0;
  for (std::size_t i = digits; i < dash; ++i) {
    if (filename[i] < '0' || filename[i] > '9') return 0;
    pid = 10 * pid + (filename[i] - '0');
  }
  return pid;
}

int remove_orphaned_temporaries(const std::filesystem::path& dir) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const long pid = temporary_owner(entry.path().filename().string());
    if (pid <= 0 || !entry.is_regular_file(ec)) continue;
    // kill(pid, 0) probes without signalling; ESRCH: no such process. A live process (even an
    // unrelated one that reused the id) keeps its files: removing a live writer's file is worse.
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    if (std::filesystem::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text;
  std::error_code ec;
  const auto size = std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;
  if (!ec && size > 0) {  // a regular file: read in one piece (a stringstream would copy it twice)
    text.resize(size);
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
    if (in.gcount() < static_cast<std::streamsize>(size) || in.peek() == std::char_traits<char>::eof()) return text;
  }
  std::stringstream ss;  // a pipe, or a file that grew while it was read: the rest
  ss << in.rdbuf();
  return text + ss.str();
}

void append_file_durable(const std::filesystem::path& path, std::string_view content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot open for appending", path);
  try {
    write_all(fd, content, path);
    if (::fsync(fd) != 0) fail("cannot flush", path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) fail("cannot close", path);
}

}  // namespace flexgait
