#pragma once
// Writing a picture: .svg as is, .png through librsvg's `rsvg-convert` (Debian librsvg2-bin,
// listed in scripts/install-deps.sh). Both atomic (temporary file + rename).
#include <string>

namespace quadapt::plot {

enum class PictureFormat { Svg, Png };

/// Format from the file extension (.svg / .png, case-insensitive). Throws InputError
/// "PATH: unknown picture format ..." otherwise — call it before doing any work.
PictureFormat picture_format(const std::string& path);

/// True when rsvg-convert is on PATH.
bool png_available();

/// Writes the SVG document `svg` to `path` (.svg or .png, see picture_format). PNG: the SVG is
/// rendered at its own pixel size on a white background by rsvg-convert, a child process
/// (core/child_process.hpp) reading a temporary SVG beside the PNG's temporary: an interrupt
/// kills it and removes both temporaries. Throws ExternalError when rsvg-convert is missing or
/// fails, InputError for an unknown extension.
void write_picture(const std::string& svg, const std::string& path);

}  // namespace quadapt::plot
