#pragma once
// Shared by the libFuzzer targets: the input bytes as a file (the readers take paths), and the
// rule for what counts as a finding. A reader may refuse any input with InputError (a clear
// one-line error, exit 2 on the command line); anything else escaping it (another exception,
// a crash, a sanitizer report, a hang) is a defect that libFuzzer reports.
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include <cstdint>
#include <cstdio>
#include <string>

#include "lib/core/errors.hpp"

namespace wr::fuzz {

// This process's scratch folder (in memory where the machine has /dev/shm: millions of cases
// write millions of files), created on first use.
inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    const std::string root = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    std::string d = root + "/wetroad-fuzz-" + std::to_string(::getpid());
    if (::mkdir(d.c_str(), 0755) != 0 && errno != EEXIST) __builtin_trap();
    return d;
  }();
  return dir;
}

// `data` written to a file named `name` in scratch_dir(); returns its path.
inline std::string as_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string path = scratch_dir() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) __builtin_trap();  // the harness itself failed: not a finding about the reader
  if (size > 0) std::fwrite(data, 1, size, f);
  std::fclose(f);
  return path;
}

// Runs `read`; InputError is the reader's documented refusal and ends the case quietly.
template <class F>
void expect_clean(F&& read) {
  try {
    read();
  } catch (const InputError&) {
  }
}

}  // namespace wr::fuzz
