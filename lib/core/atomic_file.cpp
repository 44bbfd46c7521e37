#include "core/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/error.hpp"
#include "core/path_guard.hpp"

namespace fs = std::filesystem;

namespace quadapt {

namespace {
std::string temp_name(const fs::path& p) {
  // Keep the extension last so that tools that sniff it (Gmsh) still recognise the file.
  static std::atomic<int> counter{0};
  const std::string stem = p.stem().string();
  const std::string ext = p.extension().string();
  std::string name = "." + stem + ".tmp-" + std::to_string(::getpid());
  if (int k = counter++) name += "-" + std::to_string(k);
  return (p.parent_path() / (name + ext)).string();
}

void commit(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw ExternalError(path + ": cannot write (rename failed: " + ec.message() + ")");
  }
}

// Writes through an already open stream (stdout, device, FIFO): no temporary, no rename.
void write_direct(std::ostream& out, const std::string& path,
                  const std::function<void(std::ostream&)>& writer) {
  writer(out);
  out.flush();
  if (!out) throw ExternalError(path + ": write failed");
}

void write_special(const OutputTarget& t, const std::function<void(std::ostream&)>& writer, bool binary) {
  if (t.kind == OutputTarget::Kind::Stdout) return write_direct(std::cout, "standard output", writer);
  std::ofstream out(t.path, binary ? std::ios::binary : std::ios::out);
  if (!out) throw ExternalError(t.path + ": cannot open for writing (" + std::strerror(errno) + ")");
  write_direct(out, t.path, writer);
}

}  // namespace

TempFile::TempFile(std::string path) : path_(std::move(path)), on_signal_(SignalCleanup::file(path_)) {}

TempFile::~TempFile() {
  std::error_code ec;
  if (!path_.empty()) fs::remove(path_, ec);
}

void TempFile::release() {
  path_.clear();
  on_signal_.release();
}

OutputTarget resolve_output(const std::string& path) {
  if (path.empty()) throw InputError("", "output path is empty; give a file name (or - for standard output)");
  if (path == "-") return {OutputTarget::Kind::Stdout, "-"};
  fs::path p(path);
  std::error_code ec;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    if (hops == 40) throw InputError(path, "too many levels of symbolic links");
    fs::path target = fs::read_symlink(p, ec);
    if (ec) throw InputError(path, "cannot read symbolic link (" + ec.message() + ")");
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  struct stat st {};
  if (::stat(p.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw InputError(path, "is a directory; give a file name");
    if (!S_ISREG(st.st_mode)) return {OutputTarget::Kind::Special, path};
  }
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec))
    throw InputError(path, fs::exists(dir, ec) ? dir.string() + " is not a directory"
                                               : "directory " + dir.string() + " does not exist");
  // the temporary is made there: checked now, before any work (it failed only at the end)
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw InputError(path, "directory " + dir.string() + " is not writable (" + std::strerror(errno) + ")");
  return {OutputTarget::Kind::Regular, p.string()};
}

void atomic_write(const std::string& path, const std::function<void(std::ostream&)>& writer,
                  bool binary) {
  const OutputTarget t = resolve_output(path);
  check_not_an_input(path);  // stat follows the links: the same file as t.path
  if (t.kind != OutputTarget::Kind::Regular) return write_special(t, writer, binary);
  TempFile tmp(temp_name(t.path));
  {
    std::ofstream out(tmp.path(), binary ? std::ios::binary : std::ios::out);
    if (!out) throw ExternalError(path + ": cannot open for writing (" + std::strerror(errno) + ")");
    writer(out);
    out.flush();
    if (!out) throw ExternalError(path + ": write failed (disk full?)");
  }
  commit(tmp.path(), t.path);
  tmp.release();
}

void atomic_write_via_path(const std::string& path,
                           const std::function<void(const std::string&)>& writer) {
  const OutputTarget t = resolve_output(path);
  check_not_an_input(path);  // stat follows the links: the same file as t.path
  const fs::path near = t.kind == OutputTarget::Kind::Regular
                            ? fs::path(t.path)
                            : fs::temp_directory_path() / ("quadapt" + fs::path(path).extension().string());
  TempFile tmp(temp_name(near));
  writer(tmp.path());
  if (!fs::exists(tmp.path())) throw ExternalError(path + ": the writer produced no file");
  if (t.kind == OutputTarget::Kind::Regular) {
    commit(tmp.path(), t.path);
    tmp.release();
    return;
  }
  std::ifstream in(tmp.path(), std::ios::binary);
  write_special(t, [&](std::ostream& os) { os << in.rdbuf(); }, true);
}

std::string read_text_file(const std::string& path) {
  std::ostringstream ss;
  if (path == "-") {
    ss << std::cin.rdbuf();
    return ss.str();
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open (") + std::strerror(errno) + ")");
  protect_input(path);
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace quadapt
