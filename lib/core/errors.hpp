#pragma once
// Errors the command line reports as one line: exit code 2 for bad input and options, 3 for a
// numerical failure.
#include <stdexcept>
#include <string>

namespace wr {

// Bad input: `source` names the file (or option) at fault, `problem` says what is wrong.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& source, const std::string& problem)
      : std::runtime_error(source.empty() ? problem : source + ": " + problem) {}
};

// No valid result (a non-finite value, a computation that broke down): the command line reports
// it as one line and exit code 3, and writes no output.
class NumericalError : public std::runtime_error {
 public:
  NumericalError(const std::string& source, const std::string& problem)
      : std::runtime_error(source.empty() ? problem : source + ": " + problem) {}
};

}  // namespace wr
