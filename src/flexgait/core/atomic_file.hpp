#pragma once
/// \file atomic_file.hpp
/// Files that appear whole or not at all: content goes to a temporary file in the same
/// directory, which is renamed over the target (rename is atomic on POSIX).
///
/// Atomic is not durable. A process that is killed, crashes or stops on an error at any moment
/// leaves the old target or the whole new one (the standard's "no half-written outputs"). Only a
/// power cut or a kernel crash within the kernel's write-back delay (~30 s) can lose content
/// that was renamed but not yet on disk; files that must survive that (a sweep's signature and
/// partial rows, which a resume trusts) are written durably: Durability::Durable and
/// append_file_durable(), which wait for the disk (fsync).
#include <filesystem>
#include <string>
#include <string_view>

namespace flexgait {

/// What AtomicFileWriter::commit() promises besides atomicity.
enum class Durability {
  Atomic,   ///< rename only: whole or absent under `path` whatever happens to the process
  Durable,  ///< also on disk when commit() returns (fsync of the file, then of its directory)
};

/// Throws UsageError if `path` exists and is not a regular file, symbolic links followed: a
/// directory, a character or block device (/dev/null), a FIFO or a socket. Renaming a new file
/// over such a target would replace the device or the pipe itself (as root: the system's
/// /dev/null), or fail only after the work is done. The message starts with `option` ("--out")
/// or, if it is empty, "output", and names the path, its kind and what is allowed; an empty path
/// is refused too. A path that does not exist (or a dangling link, which the rename replaces)
/// passes.
void check_output_file(const std::filesystem::path& path, const std::string& option = "");

/// Throws UsageError (message as check_output_file's) if `path` is empty, exists and is not a directory,
/// or if one of its entries is neither a regular file nor a directory (links followed): a run
/// directory's files are replaced by rename, which must not land on a device, FIFO or socket.
void check_output_directory(const std::filesystem::path& path, const std::string& option = "");

/// Renames the file `tmp` to `target` if `target` is absent or a regular file (links followed);
/// never replaces a directory, device, FIFO or socket, even one that appears during the call.
/// Throws UsageError (check_output_file's message; `tmp` and `target` as they were) or
/// std::system_error; `tmp` is the caller's to remove on failure.
void rename_over_regular_file(const std::filesystem::path& tmp, const std::filesystem::path& target);

/// Writes `content` to `path` atomically. Throws std::system_error on failure, leaving
/// neither a partial `path` nor a temporary file behind.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// As write_file_atomic, and on disk when it returns (Durability::Durable).
void write_file_durable(const std::filesystem::path& path, std::string_view content);

/// A file written in pieces that appears whole or not at all: the pieces go to a temporary file
/// beside `path` (".NAME.tmp-PID-XXXXXX", see temporary_owner()); commit() renames it over `path`
/// (after flushing it to disk if Durability::Durable).
/// Destroyed without commit() (an exception, an early return), it removes the temporary file and
/// `path` is untouched. A process killed mid-way leaves at most the temporary file, never a
/// half-written `path`.
class AtomicFileWriter {
 public:
  /// Creates the temporary file. Throws UsageError if `path` exists and is not a regular file
  /// (check_output_file), std::system_error if the temporary file cannot be made.
  explicit AtomicFileWriter(std::filesystem::path path, Durability durability = Durability::Atomic);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  /// Appends `content` to the temporary file. Throws std::system_error on failure.
  void append(std::string_view content);
  /// Closes the temporary file and renames it over the target (once; Durable: with an fsync of
  /// the file before and of the directory after). The rename never replaces what is not a
  /// regular file, even one put there after the constructor's check: on Linux it creates the
  /// name or swaps atomically and swaps back a special file it found (renameat2).
  /// Throws UsageError (check_output_file) or std::system_error on failure, leaving neither a
  /// partial target nor the temporary file.
  void commit();
  const std::filesystem::path& path() const { return path_; }
  /// The temporary file's path (while not committed).
  const std::filesystem::path& temporary_path() const { return tmp_; }

 private:
  void discard() noexcept;
  std::filesystem::path path_, tmp_;
  Durability durability_;
  int fd_ = -1;
};

/// The process id that owns a temporary file named by the project's scheme ".NAME.tmp-PID-XXXXXX"
/// (AtomicFileWriter here, `atomic_write.py` in the Python scripts), or 0 if `filename` is not one.
long temporary_owner(const std::string& filename);

/// Removes the temporary files in `dir` (not recursively) whose owning process no longer exists:
/// what a killed writer left behind. Temporaries of live processes are kept. Returns how many
/// were removed; errors (a file vanishing meanwhile) are ignored.
int remove_orphaned_temporaries(const std::filesystem::path& dir);

/// The whole content of a file ("" if it cannot be read).
std::string read_text_file(const std::filesystem::path& path);

/// Appends `content` to `path` (creating it) and flushes it to disk; used for records that must
/// survive an interruption one line at a time (sweeps). Throws std::system_error on failure.
void append_file_durable(const std::filesystem::path& path, std::string_view content);

}  // namespace flexgait
