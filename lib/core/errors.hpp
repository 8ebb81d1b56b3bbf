#pragma once
// Errors the command line reports as one line and exit code 2 (bad input, bad options).
#include <stdexcept>
#include <string>

namespace wr {

// Bad input: `source` names the file (or option) at fault, `problem` says what is wrong.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& source, const std::string& problem)
      : std::runtime_error(source.empty() ? problem : source + ": " + problem) {}
};

}  // namespace wr
