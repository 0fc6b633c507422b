#pragma once
/// \file atomic_file.hpp
/// Files that appear whole or not at all: content goes to a temporary file in the same
/// directory, which is flushed to disk and renamed over the target (rename is atomic on POSIX).
#include <filesystem>
#include <string>
#include <string_view>

namespace flexgait {

/// Writes `content` to `path` atomically. Throws std::system_error on failure, leaving
/// neither a partial `path` nor a temporary file behind.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// The whole content of a file ("" if it cannot be read).
std::string read_text_file(const std::filesystem::path& path);

/// Appends `content` to `path` (creating it) and flushes it to disk; used for records that must
/// survive an interruption one line at a time (sweeps). Throws std::system_error on failure.
void append_file_durable(const std::filesystem::path& path, std::string_view content);

}  // namespace flexgait
