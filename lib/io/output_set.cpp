#include "lib/io/output_set.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/staging.hpp"

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

// What `path` is when it exists and is not a regular file (a FIFO, a device, a socket): writing
// there would replace the node (as root) or block; "" for a regular file or no file.
std::string special_kind(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISLNK(st.st_mode) && ::stat(path.c_str(), &st) != 0) return "";  // a dangling link: a new file
  if (S_ISREG(st.st_mode) || S_ISDIR(st.st_mode)) return "";
  if (S_ISFIFO(st.st_mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(st.st_mode)) return "a character device";
  if (S_ISBLK(st.st_mode)) return "a block device";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "not a regular file";
}

// Holds flock()s on the folders an output set is committed into, taken in one order (by device
// and inode) so that two commands committing into the same folders never deadlock, and released
// on destruction. Two runs writing the same outputs thus rename their sets one after the other:
// the last set wins whole, never a mixture of both.
class FolderLocks {
 public:
  explicit FolderLocks(const std::vector<std::string>& folders) {
    std::vector<std::pair<std::pair<dev_t, ino_t>, std::string>> keyed;
    for (const auto& f : folders) {
      struct stat st {};
      if (::stat(f.c_str(), &st) == 0) keyed.push_back({{st.st_dev, st.st_ino}, f});
    }
    std::sort(keyed.begin(), keyed.end());
    keyed.erase(std::unique(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
                keyed.end());
    for (const auto& [key, f] : keyed) {
      const int fd = ::open(f.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (fd < 0) continue;  // the renames below report a folder that vanished
      while (::flock(fd, LOCK_EX) != 0 && errno == EINTR) {
      }
      fds_.push_back(fd);
    }
  }
  ~FolderLocks() {
    for (int fd : fds_) ::close(fd);  // closing releases the lock
  }
  FolderLocks(const FolderLocks&) = delete;
  FolderLocks& operator=(const FolderLocks&) = delete;

 private:
  std::vector<int> fds_;
};

std::string folder_of(const std::string& path) {
  const fs::path p = fs::path(path).lexically_normal();
  fs::path parent = p.filename().empty() ? p.parent_path().parent_path() : p.parent_path();
  return parent.empty() ? std::string(".") : parent.string();
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
  for (const Entry& e : outputs_) {
    fs::remove_all(e.staged, ec);
    untrack_staging(e.staged);
  }
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
  if (const std::string kind = special_kind(path); !kind.empty())
    throw InputError(option + " " + path, "exists and is " + kind + ", not a regular file; give a file name");
  if (writes_) remove_stale_staging(path);
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
  if (writes_) remove_stale_staging(dir);
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
    untrack_staging(e.staged);
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
      untrack_staging(it->staged);
      outputs_.erase(it);
      return;
    }
}

void OutputSet::commit() {
  if (!writes_ || committed_) return;
  std::vector<std::string> folders;
  for (const Entry& e : outputs_) folders.push_back(folder_of(e.final_path));
  const FolderLocks locks(folders);
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
    untrack_staging(e.staged);
  }
  committed_ = true;
}

}  // namespace wr
