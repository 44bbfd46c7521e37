#pragma once
// Typed errors thrown by library code. Only tools (through cli/tool_runner) turn them into
// messages and exit codes; library code never calls exit().
#include <stdexcept>
#include <string>

namespace quadapt {

/// Base of every quadapt error. what() is a complete one-line message.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Bad input from the user: a malformed or unreadable file, a missing field, a wrong element
/// type, an inverted element, an invalid option value. Message form: "FILE: problem".
struct InputError : Error {
  using Error::Error;
  /// Builds "file: problem" (or just "problem" when file is empty).
  InputError(const std::string& file, const std::string& problem)
      : Error(file.empty() ? problem : file + ": " + problem) {}
};

/// A numerical method that could not deliver (singular system, no convergence where the
/// result would be meaningless). Message says what failed and what to try.
struct NumericalError : Error {
  using Error::Error;
};

/// Failure of an external component (Gmsh SDK, ffbamg, file system).
struct ExternalError : Error {
  using Error::Error;
};

}  // namespace quadapt
