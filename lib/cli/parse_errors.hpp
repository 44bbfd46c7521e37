#pragma once
// Command-line mistakes a person can act on (lib/cli/tool.hpp's runner uses these):
//  - an unknown option is named, even when CLI11 would first complain about a missing
//    required argument ("dgsolve --bogus" -> "unknown option --bogus");
//  - numbers in CLI11's messages are printed in %.3e (its numeric range validators print the
//    largest double as 310 digits);
//  - validators for positive / non-negative numbers with short messages.
#include <CLI/CLI.hpp>
#include <string>

namespace quadapt {

/// The first argument of argv[1..] that looks like an option ("-x", "--name", "--name=v") and
/// that `app` does not define; "" when there is none. "-", and "-" followed by a digit or "."
/// (negative numbers, values like "-6,4"), are not options.
std::string first_unknown_option(const CLI::App& app, int argc, char** argv);

/// The message for a CLI11 parse error: the unknown option when there is one, a file_problem as
/// it is, else e.what() with every number longer than 12 characters reprinted in %.3e.
std::string parse_error_message(const CLI::App& app, int argc, char** argv, const CLI::ParseError& e);

/// A validator's message about the file it was given rather than the option ("FILE: no such
/// file"): parse_error_message then prints it as it is, without the option name CLI11 puts
/// first ("MESH: ..."), so that it reads "TOOL: FILE: problem" like every other file message.
std::string file_problem(const std::string& file, const std::string& problem);
/// Whether `e` carries a file_problem (the runner adds no "(see TOOL --help)" to it).
bool is_file_problem(const CLI::ParseError& e);

/// Validators: value > 0, value >= 0 ("must be > 0 (got -1)").
extern const CLI::Validator PositiveValue;
extern const CLI::Validator NonNegativeValue;

}  // namespace quadapt
