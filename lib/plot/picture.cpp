#include "plot/picture.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <ostream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace fs = std::filesystem;

namespace quadapt::plot {

namespace {
std::string shell_quote(const std::string& s) {
  std::string r = "'";
  for (char c : s) {
    if (c == '\'') r += "'\\''";
    else r += c;
  }
  return r + "'";
}
}  // namespace

PictureFormat picture_format(const std::string& path) {
  if (path == "-") return PictureFormat::Svg;  // standard output
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".svg") return PictureFormat::Svg;
  if (ext == ".png") return PictureFormat::Png;
  throw InputError(path, "unknown picture format '" + ext + "' (use .svg or .png)");
}

bool png_available() { return std::system("command -v rsvg-convert >/dev/null 2>&1") == 0; }

void write_picture(const std::string& svg, const std::string& path) {
  if (picture_format(path) == PictureFormat::Svg) {
    atomic_write(path, [&](std::ostream& os) { os << svg; });
    return;
  }
  if (!png_available())
    throw ExternalError(path + ": cannot write PNG: rsvg-convert not found (install librsvg2-bin, "
                        "see scripts/install-deps.sh) — or write .svg");
  atomic_write_via_path(path, [&](const std::string& tmp) {
    const std::string svg_tmp = tmp + ".svg";
    atomic_write(svg_tmp, [&](std::ostream& os) { os << svg; });
    const std::string cmd = "rsvg-convert -f png -b white -o " + shell_quote(tmp) + " " + shell_quote(svg_tmp) +
                            " 2>/dev/null";
    int rc = std::system(cmd.c_str());
    std::error_code ec;
    fs::remove(svg_tmp, ec);
    if (rc != 0 || !fs::exists(tmp))
      throw ExternalError(path + ": rsvg-convert failed (exit " +
                          std::to_string(WIFEXITED(rc) ? WEXITSTATUS(rc) : -1) + ")");
  });
}

}  // namespace quadapt::plot
