#include "core/standard_input.hpp"

#include <iostream>
#include <iterator>

#include "core/error.hpp"
#include "core/sha256.hpp"

namespace quadapt {

namespace {
struct StandardInput {
  bool read = false;
  std::string bytes;
  std::string sha256;
};
StandardInput& state() {
  static StandardInput s;
  return s;
}
}  // namespace

const std::string& standard_input() {
  StandardInput& s = state();
  if (!s.read) {
    s.bytes.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    if (std::cin.bad()) throw InputError("-", "cannot read standard input");
    s.sha256 = sha256_hex(s.bytes);
    s.read = true;
  }
  return s.bytes;
}

std::optional<std::string> standard_input_sha256() {
  const StandardInput& s = state();
  if (!s.read) return std::nullopt;
  return s.sha256;
}

}  // namespace quadapt
