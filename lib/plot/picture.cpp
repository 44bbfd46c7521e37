#include "plot/picture.hpp"

#include <filesystem>
#include <fstream>

#include "core/atomic_file.hpp"
#include "core/child_process.hpp"
#include "core/error.hpp"
#include "core/file_name.hpp"

namespace fs = std::filesystem;

namespace quadapt::plot {

PictureFormat picture_format(const std::string& path) {
  if (path == "-") return PictureFormat::Svg;  // standard output
  const std::string ext = lower_extension(path);
  if (ext == ".svg") return PictureFormat::Svg;
  if (ext == ".png") return PictureFormat::Png;
  throw InputError(path, "unknown picture format '" + ext + "' (use .svg or .png)");
}

bool png_available() { return on_path("rsvg-convert"); }

void write_picture(const std::string& svg, const std::string& path) {
  if (picture_format(path) == PictureFormat::Svg) {
    atomic_write(path, [&](std::ostream& os) { os << svg; });
    return;
  }
  if (!png_available())
    throw ExternalError(path + ": cannot write PNG: rsvg-convert not found (install librsvg2-bin, "
                        "see scripts/install-deps.sh) — or write .svg");
  atomic_write_via_path(path, [&](const std::string& tmp) {
    // the SVG beside the PNG's temporary; both removed on every exit path and by the signal
    // handler, which also kills rsvg-convert (core/child_process.hpp)
    const TempFile svg_tmp(tmp + ".svg");
    {
      std::ofstream os(svg_tmp.path());
      os << svg;
      os.flush();
      if (!os) throw ExternalError(path + ": cannot write the temporary " + svg_tmp.path());
    }
    const ChildExit ex = run_child({"rsvg-convert", "-f", "png", "-b", "white", "-o", tmp, svg_tmp.path()});
    if (!ex.ok() || !fs::exists(tmp)) throw ExternalError(path + ": rsvg-convert failed (" + ex.how() + ")");
  });
}

}  // namespace quadapt::plot
