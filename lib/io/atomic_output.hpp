#pragma once
// Output files appear whole or not at all: write to a temporary name in the same directory,
// then rename() over the target (atomic on POSIX within one file system).
#include <string>

namespace wr {

// A temporary path next to `final_path` (same directory, unique per process and call), ending in
// `suffix`; tracked as a staging path (lib/io/staging.hpp) until commit_file renames it.
std::string temporary_sibling(const std::string& final_path, const std::string& suffix = "");

// Writes `content` to `final_path` atomically; throws InputError(final_path, ...) on failure.
void write_text_atomically(const std::string& final_path, const std::string& content);

// Renames `tmp` onto `final_path` and untracks it; removes `tmp` and throws InputError on failure.
void commit_file(const std::string& tmp, const std::string& final_path);

}  // namespace wr
