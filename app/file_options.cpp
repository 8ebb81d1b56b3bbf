#include "app/file_options.hpp"

#include <sys/stat.h>

#include <string>
#include <utility>
#include <vector>

#include "lib/core/errors.hpp"
#include "lib/io/output_set.hpp"

namespace wr::app {
namespace {

using Named = std::vector<std::pair<std::string, std::string>>;  // (option, path)

std::string option_name(const CLI::Option* o) {
  if (!o->get_lnames().empty()) return "--" + o->get_lnames().front();
  if (!o->get_snames().empty()) return "-" + o->get_snames().front();
  return o->get_name();  // a positional
}

// The mark without what validators append to it ("FILE:FILE" for an option also checked by
// CLI::ExistingFile).
std::string mark_of(const CLI::Option* o) {
  const std::string t = o->get_type_name();
  return t.substr(0, t.find(':'));
}

Named values_of(const CLI::App& sub, const std::string& type) {
  Named out;
  for (const CLI::Option* o : sub.get_options())
    if (mark_of(o) == type && o->count() > 0)
      for (const std::string& v : o->results()) {
        if (v.empty()) throw InputError(option_name(o), "is empty; give a file name");
        out.emplace_back(option_name(o), v);
      }
  return out;
}

// Why an existing input cannot be read as a file; "" when it is a regular file or absent (the
// reader names a missing file; --scene also takes built-in names).
std::string unreadable_kind(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return "is a folder; give a file";
  const char* what = S_ISFIFO(st.st_mode) ? "a FIFO or pipe (e.g. <(...))"
                     : S_ISCHR(st.st_mode) ? "a character device"
                     : S_ISBLK(st.st_mode) ? "a block device"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                                            : "not a regular file";
  return std::string("is ") + what + ", not a regular file: inputs are read more than once; save it to a file first";
}

void check_one(const CLI::App& sub) {
  const Named inputs = values_of(sub, "FILE");
  for (const auto& [opt, path] : inputs)
    if (const std::string why = unreadable_kind(path); !why.empty()) throw InputError(path, opt + ": " + why);
  for (const char* type : {"OUTPUT", "FOLDER"})
    for (const auto& [out_opt, out] : values_of(sub, type))
      for (const auto& [in_opt, in] : inputs)
        if (same_file(out, in))
          throw InputError(out_opt + " " + out,
                           "is an input of this command (" + in_opt + " " + in + "); writing it would destroy it");
}

}  // namespace

void check_file_options(const CLI::App& sub) {
  check_one(sub);
  for (const CLI::App* child : sub.get_subcommands()) check_file_options(*child);
}

}  // namespace wr::app
