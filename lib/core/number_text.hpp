#pragma once
// A number as messages print it: `digits` significant digits, shortest form ("0.05", "3.14e+05").
#include <sstream>
#include <string>

namespace wr {

inline std::string number_text(double x, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

}  // namespace wr
