#include "lib/io/output_set.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"

namespace wr {
namespace fs = std::filesystem;

namespace {

// The absolute, normalised spelling of `p` with every symbolic link of its existing part
// resolved (weakly_canonical), so "./a", "x/../a" and a link to "a" compare equal.
fs::path normalised(const std::string& p) {
  std::error_code ec;
  fs::path out = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) out = fs::absolute(p, ec).lexically_normal();
  return out;
}

// Creates an empty file at `path` (fails if it exists); the error text on failure.
std::string create_empty(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) return std::strerror(errno);
  ::close(fd);
  return "";
}

std::string why_not_writable(const std::string& dir, const std::string& error) {
  std::error_code ec;
  const fs::path d = dir.empty() ? fs::path(".") : fs::path(dir);
  if (!fs::exists(d, ec)) return "cannot write: directory " + d.string() + " does not exist";
  if (!fs::is_directory(d, ec)) return "cannot write: " + d.string() + " is not a directory";
  return "cannot write: " + error;
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return normalised(a) == normalised(b);
}

OutputSet::~OutputSet() {
  if (committed_ || !writes_) return;
  std::error_code ec;
  for (const Entry& e : outputs_) fs::remove_all(e.staged, ec);
}

void OutputSet::input(const std::string& path) {
  if (!path.empty()) inputs_.push_back(path);
}

void OutputSet::check_distinct(const std::string& option, const std::string& path) const {
  for (const auto& in : inputs_)
    if (same_file(path, in))
      throw InputError(option + " " + path, "is an input of this command (" + in + "); writing it would destroy it");
  for (const auto& out : outputs_)
    if (same_file(path, out.final_path))
      throw InputError(option + " " + path, "is also the output of " + out.option + "; give each output its own file");
}

std::string OutputSet::add(const std::string& option, const std::string& path) {
  if (path.empty()) return "";
  check_distinct(option, path);
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(option + " " + path, "is a directory; give a file name");
  const std::string staged = temporary_sibling(path);
  if (const std::string err = create_empty(staged); !err.empty())
    throw InputError(option + " " + path, why_not_writable(fs::path(path).parent_path().string(), err));
  return keep({option, path, staged, false});
}

std::string OutputSet::add_directory(const std::string& option, const std::string& dir) {
  if (dir.empty()) return "";
  check_distinct(option, dir);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(option + " " + dir, "exists and is not a directory");
  // Stage beside the folder (same file system, so the final moves are renames).
  fs::path normal = fs::path(dir).lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();  // "charts/" -> "charts"
  const fs::path parent = normal.parent_path();
  const std::string staged = temporary_sibling(normal.string());
  if (!fs::create_directory(staged, ec))
    throw InputError(option + " " + dir, why_not_writable(parent.string(), ec.message()));
  return keep({option, dir, staged, true});
}

std::string OutputSet::keep(Entry e) {
  if (!writes_) {  // the staging only proved the output writable: this process writes nothing
    std::error_code ec;
    fs::remove(e.staged, ec);
    e.staged = e.final_path;
  }
  outputs_.push_back(e);
  return e.staged;
}

void OutputSet::discard(const std::string& option) {
  std::error_code ec;
  for (auto it = outputs_.begin(); it != outputs_.end(); ++it)
    if (it->option == option) {
      if (writes_) fs::remove_all(it->staged, ec);
      outputs_.erase(it);
      return;
    }
}

void OutputSet::commit() {
  if (!writes_ || committed_) return;
  for (const Entry& e : outputs_) {
    if (!e.directory) {
      commit_file(e.staged, e.final_path);
      continue;
    }
    std::error_code ec;
    fs::create_directories(e.final_path, ec);
    if (ec) throw InputError(e.final_path, "cannot create the directory: " + ec.message());
    for (const auto& f : fs::directory_iterator(e.staged))
      commit_file(f.path().string(), (fs::path(e.final_path) / f.path().filename()).string());
    fs::remove(e.staged, ec);
  }
  committed_ = true;
}

}  // namespace wr
