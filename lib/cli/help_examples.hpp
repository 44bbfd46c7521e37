#pragma once
// The example that ends each tool's --help (one command a user can paste, from the repository's
// root, with what it writes). Kept here, beside the runner, so every tool has one (tested).
#include <string>

namespace quadapt {

/// The example for tool `name` ("Example:\n  CMD\n  # what it does"), or "" when there is none.
std::string help_example(const std::string& name);

}  // namespace quadapt
