#include "lib/io/input_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "lib/core/errors.hpp"

namespace wr {

std::string read_input_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a " + what);
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(path, "is not a regular file (a pipe, device or socket); save the " + what + " to a file first");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the " + what);
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(path, "cannot read the " + what);
  return s.str();
}

}  // namespace wr
