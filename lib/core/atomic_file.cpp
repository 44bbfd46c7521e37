#include "core/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <memory>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/error.hpp"
#include "core/path_guard.hpp"
#include "core/standard_input.hpp"

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

void commit_rename(const std::string& tmp, const std::string& path) {
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

struct OutputBatch::Item {
  OutputTarget target;
  std::unique_ptr<TempFile> tmp;  // regular targets: the written temporary
  std::string text;               // special targets: the content, written at commit
  bool binary = false;
};

OutputBatch::OutputBatch() = default;
OutputBatch::~OutputBatch() = default;  // uncommitted temporaries are removed by their TempFile

void OutputBatch::add(const std::string& path, const std::function<void(std::ostream&)>& writer, bool binary) {
  add(resolve_output(path), path, writer, binary);
}

void OutputBatch::add(const OutputTarget& target, const std::string& path,
                      const std::function<void(std::ostream&)>& writer, bool binary) {
  if (committed_) throw NumericalError("OutputBatch::add after commit");
  Item it;
  it.target = target;
  check_not_an_input(path);  // stat follows the links: the same file as target.path
  it.binary = binary;
  if (it.target.kind != OutputTarget::Kind::Regular) {
    // run now like the others (the writer's captures need not outlive add), written at commit
    std::ostringstream os(binary ? std::ios::out | std::ios::binary : std::ios::out);
    writer(os);
    it.text = std::move(os).str();
  } else {
    it.tmp = std::make_unique<TempFile>(temp_name(it.target.path));
    std::ofstream out(it.tmp->path(), binary ? std::ios::binary : std::ios::out);
    if (!out) throw ExternalError(path + ": cannot open for writing (" + std::strerror(errno) + ")");
    errno = 0;
    writer(out);
    out.flush();
    // the failed write(2)'s reason (No space left on device, File too large) when it set one
    if (!out) throw ExternalError(path + ": write failed (" + (errno ? std::string(std::strerror(errno)) : "disk full?") + ")");
  }
  items_.push_back(std::move(it));
}

void OutputBatch::after_commit(std::function<void()> f) { after_.push_back(std::move(f)); }

void OutputBatch::commit() {
  if (committed_) return;
  committed_ = true;
  // devices and standard output first (their writes can fail: /dev/full), then the renames
  for (Item& it : items_)
    if (it.target.kind != OutputTarget::Kind::Regular)
      write_special(it.target, [&](std::ostream& os) { os << it.text; }, it.binary);
  for (Item& it : items_) {
    if (it.target.kind != OutputTarget::Kind::Regular) continue;
    commit_rename(it.tmp->path(), it.target.path);
    it.tmp->release();
  }
  for (auto& f : after_) f();
}

void atomic_write(const std::string& path, const std::function<void(std::ostream&)>& writer,
                  bool binary) {
  const OutputTarget t = resolve_output(path);
  if (t.kind != OutputTarget::Kind::Regular) {  // streamed, not held in memory
    check_not_an_input(path);
    return write_special(t, writer, binary);
  }
  OutputBatch b;
  b.add(t, path, writer, binary);
  b.commit();
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
    commit_rename(tmp.path(), t.path);
    tmp.release();
    return;
  }
  std::ifstream in(tmp.path(), std::ios::binary);
  write_special(t, [&](std::ostream& os) { os << in.rdbuf(); }, true);
}

std::string read_text_file(const std::string& path) {
  std::ostringstream ss;
  if (path == "-") return standard_input();  // read once, its sha256 kept for the report
  // a directory opens, then its read threw std::ios_base::failure past the typed errors (a library
  // user's review, session 38)
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open (") + std::strerror(errno) + ")");
  protect_input(path);
  try {
    ss << in.rdbuf();
  } catch (const std::ios_base::failure& e) {
    throw InputError(path, std::string("cannot read (") + e.what() + ")");
  }
  if (in.bad()) throw InputError(path, "cannot read (a read error)");
  return ss.str();
}

}  // namespace quadapt
