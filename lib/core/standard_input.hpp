#pragma once
// Standard input, read whole once: a tool that reads an input from "-" (a mesh, a frame, a case)
// gets its bytes from here, so that the report's provenance can state their SHA-256 as it does
// for a file's (cli/provenance.hpp; a piped chain had "input_sha256": {"-": null}).
#include <optional>
#include <string>

namespace quadapt {

/// All of standard input, read on the first call (later calls return the same bytes: standard
/// input is read once per process). Throws InputError("-: ...") if the read fails.
const std::string& standard_input();

/// SHA-256 (64 hex digits) of standard input's bytes once standard_input() has read them; none
/// before (the process read no input from "-").
std::optional<std::string> standard_input_sha256();

}  // namespace quadapt
