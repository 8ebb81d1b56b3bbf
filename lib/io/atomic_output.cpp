#include "lib/io/atomic_output.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "lib/core/errors.hpp"
#include "lib/io/staging.hpp"

namespace wr {

std::string temporary_sibling(const std::string& final_path, const std::string& suffix) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path p(final_path);
  const std::string name = "." + p.filename().string() + ".tmp-" + std::to_string(::getpid()) +
                           "-" + std::to_string(counter++) + suffix;
  const std::string tmp = (p.parent_path() / name).string();
  track_staging(tmp);
  return tmp;
}

void commit_file(const std::string& tmp, const std::string& final_path) {
  if (std::rename(tmp.c_str(), final_path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    untrack_staging(tmp);
    throw InputError(final_path, "cannot write: " + why);
  }
  untrack_staging(tmp);
}

void write_text_atomically(const std::string& final_path, const std::string& content) {
  const std::string tmp = temporary_sibling(final_path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(final_path, std::string("cannot write: ") + std::strerror(errno));
    out << content;
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw InputError(final_path, "write failed (disk full?)");
    }
  }
  commit_file(tmp, final_path);
}

}  // namespace wr
