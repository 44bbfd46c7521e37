#include "core/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace fs = std::filesystem;

namespace quadapt {

namespace {
std::string temp_name(const std::string& path) {
  // Keep the extension last so that tools that sniff it (Gmsh) still recognise the file.
  fs::path p(path);
  std::string stem = p.stem().string();
  std::string ext = p.extension().string();
  fs::path dir = p.parent_path();
  return (dir / ("." + stem + ".tmp-" + std::to_string(::getpid()) + ext)).string();
}

void commit(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw ExternalError(path + ": cannot write (rename failed: " + ec.message() + ")");
  }
}
}  // namespace

void atomic_write(const std::string& path, const std::function<void(std::ostream&)>& writer,
                  bool binary) {
  const std::string tmp = temp_name(path);
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary : std::ios::out);
      if (!out) throw ExternalError(path + ": cannot open for writing (" + std::strerror(errno) + ")");
      writer(out);
      out.flush();
      if (!out) throw ExternalError(path + ": write failed (disk full?)");
    }
    commit(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void atomic_write_via_path(const std::string& path,
                           const std::function<void(const std::string&)>& writer) {
  const std::string tmp = temp_name(path);
  try {
    writer(tmp);
    if (!fs::exists(tmp)) throw ExternalError(path + ": the writer produced no file");
    commit(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void check_not_an_input(const std::string& output, const std::vector<std::string>& inputs) {
  std::error_code ec;
  for (const auto& in : inputs) {
    if (in.empty()) continue;
    bool same = false;
    if (fs::exists(output, ec) && fs::exists(in, ec)) {
      same = fs::equivalent(output, in, ec);
    } else {
      same = fs::absolute(output).lexically_normal() == fs::absolute(in).lexically_normal();
    }
    if (same)
      throw InputError(output, "output would overwrite the input file " + in +
                                   "; choose another output path");
  }
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open (") + std::strerror(errno) + ")");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace quadapt
