#pragma once
// Numeric options checked at parse time, for every tool, from one table (option_ranges.cpp).
//
// Every floating-point option must be finite (CLI11's own Range/PositiveNumber let NaN through);
// an option listed in the table must lie in its range. A failed check is a CLI11 ValidationError:
// the runner prints "TOOL: --rtol: -1 is not in (0, 1) ..." and exits 2 before anything is read
// or written. The table is the one place the ranges live; docs/exit-codes.md lists them.
#include <CLI/CLI.hpp>
#include <string>

namespace quadapt {

/// One row: `tool` ("*" for every tool) and the option's long name ("--rtol"); the interval
/// from lo to hi, each end open or closed (hi may be infinity); `zero_off`: 0 is accepted too
/// (the option's "off", e.g. --gradation: 0 or a growth > 1).
struct OptionRange {
  const char* tool;
  const char* option;
  double lo, hi;
  bool lo_open, hi_open;
  bool zero_off = false;
};

/// The table.
const std::vector<OptionRange>& option_ranges();

/// Attaches to the options of `app` (of the tool `tool`) the finiteness check and the ranges of
/// the table, and replaces CLI11's ExistingFile by one that also accepts "-" (standard input).
/// Called by Tool::run before parsing, so the tools' own option code needs no change.
void apply_option_ranges(const std::string& tool, CLI::App& app);

/// The number of OpenMP threads a tool may use: `requested` (0 = OpenMP's default) clamped to
/// [1, 4 x the processors this process can run on] (the OpenMP runtime crashes on absurd counts).
int clamp_threads(long requested);

}  // namespace quadapt
