#pragma once
// Never overwrite an input: the one check every tool's writes go through.
//
// A file is identified by (device, inode) of what its path finally names, so the check sees
// through symlinks, hard links and `..` alike. Tools (lib/cli/tool) declare every path they read
// with protect_input() and every path they will write with check_output_path(); atomic_write
// (core/atomic_file) repeats the check on the resolved target before it creates anything, so a
// write that no tool declared is still refused. The registry is process-wide and off until
// enable_input_guard() (the tool runner turns it on; library unit tests leave it off).
//
// "-" is standard input / output and never conflicts with a file.
#include <string>

namespace quadapt {

/// True if `a` and `b` both exist and are the same file (same st_dev and st_ino after following
/// symlinks). False when either does not exist.
bool same_file(const std::string& a, const std::string& b);

/// Turns the process-wide input registry on (Tool::run does this) or off.
void enable_input_guard(bool on = true);

/// Records `path` as an input of this process (no-op for "-", a missing file, or when the guard
/// is off). Throws InputError if it is a file already declared as an output.
void protect_input(const std::string& path);

/// Records `path` as an output of this process. Throws InputError "PATH: output would overwrite
/// the input file IN; choose another output path" if it is (or resolves to) a protected input.
/// `role`, when given, names the output in that message instead, with its own remedy (e.g. a
/// report written beside the output: "the report written beside OUT ... (--report PATH)").
void protect_output(const std::string& path, const std::string& role = "", const std::string& remedy = "");

/// Throws InputError if writing `path` would replace a protected input (see protect_output);
/// does not record it. Called by every atomic_write.
void check_not_an_input(const std::string& path);

/// Forgets every recorded input and output (tests).
void clear_protected_paths();

}  // namespace quadapt
