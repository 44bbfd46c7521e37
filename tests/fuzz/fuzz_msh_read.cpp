// libFuzzer target: the .msh reader (MSH 4.1 / 2.2, ASCII and binary), the validator and the
// $SolvedCase record's parse on arbitrary bytes. Every rejection must be a quadapt::Error (a
// one-line "PATH: problem"); any other exception, a crash, a leak or undefined behaviour is a bug
// (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

#include "case/solved_case.hpp"
#include "core/error.hpp"
#include "io/msh.hpp"
#include "mesh/validate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    quadapt::Mesh m = quadapt::read_msh(in, "fuzz.msh");
    quadapt::validate_mesh(m, "fuzz.msh");
    if (!m.solved_case.empty()) quadapt::solved_penalty(m.solved_case, "fuzz.msh");  // adjoint's parse
  } catch (const quadapt::Error&) {
    // a clean rejection
  } catch (const std::exception& e) {
    std::cerr << "non-quadapt exception (exit 3 in a tool): " << e.what() << std::endl;
    std::abort();
  }
  return 0;
}
