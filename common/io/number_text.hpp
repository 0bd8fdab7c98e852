#pragma once
// Numbers in messages as people write them ("10", "0.74", "1e-05"): six
// significant digits, no trailing zeros — not std::to_string's "10.000000".
// (exact_number.hpp writes numbers that must read back bit for bit.)
#include <sstream>
#include <string>

namespace tankfsi {

inline std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace tankfsi
