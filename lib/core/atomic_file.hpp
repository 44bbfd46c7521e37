#pragma once
// Output files: what a path given to -o / --report means, and writing it so that a reader (or an
// interrupted Makefile loop) never sees a half-written file.
//
// resolve_output(path):
//   "-"                      standard output (written directly)
//   a regular file or a new  written to a temporary file beside it, then renamed over it
//     name                     (atomic replace)
//   a symlink                followed (up to 40 links) and the rule applied to its final target,
//                              so the link stays and its target is replaced
//   a device, FIFO, socket   opened and written directly (no temporary, no rename)
//   "" / a directory / a     InputError "PATH: ..." before anything is written
//     missing parent folder
// Every write first checks (core/path_guard) that the final target is not an input.
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/signal_cleanup.hpp"

namespace quadapt {

struct OutputTarget {
  enum class Kind { Stdout, Regular, Special };
  Kind kind = Kind::Regular;
  /// The path to write: for Regular the final target of any symlinks (the temporary is made
  /// beside it); for Special the path as given; "-" for Stdout.
  std::string path;
};

/// Classifies `path` as above. Throws InputError for "", a directory, a missing parent
/// directory, or a symlink loop.
OutputTarget resolve_output(const std::string& path);

/// Writes `path` (see resolve_output): for a regular file `writer` fills a stream on a
/// temporary ".STEM.tmp-PID.EXT" beside the target, which is renamed over it only if writer
/// returns normally and the stream is good; on any exception the temporary is removed and the
/// exception propagates. Throws ExternalError on I/O failure.
void atomic_write(const std::string& path, const std::function<void(std::ostream&)>& writer,
                  bool binary = false);

/// Several outputs replaced as one (a mesh and its Gmsh options file, a tool's main output and
/// its side outputs): add() runs the writer at once, into a temporary beside a regular target
/// (for standard output or a device into memory, so the writer's captures need not outlive add());
/// commit() writes the devices and standard output (in the order added), then renames every
/// temporary over its target. An exception before commit() — a failed write, a full disk, a
/// refused path — removes every temporary and replaces no target, so a tool that exits 2 has
/// written nothing. Each path is checked as atomic_write checks it (resolve_output, not an input).
class OutputBatch {
 public:
  OutputBatch();
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;
  void add(const std::string& path, const std::function<void(std::ostream&)>& writer, bool binary = false);
  /// Runs `f` after the renames (e.g. removing a stale side file); its exceptions propagate.
  void after_commit(std::function<void()> f);
  void commit();

 private:
  struct Item;
  /// add() with its path already resolved (atomic_write resolves it once, to choose streaming)
  void add(const OutputTarget& target, const std::string& path, const std::function<void(std::ostream&)>& writer,
           bool binary);
  friend void atomic_write(const std::string&, const std::function<void(std::ostream&)>&, bool);
  std::vector<Item> items_;
  std::vector<std::function<void()>> after_;
  bool committed_ = false;
};

/// Same, for writers that need a file name (e.g. an external program): `writer` receives a
/// temporary path to create (same extension as `path`); it is renamed to the target afterwards,
/// or copied to standard output / the device.
void atomic_write_via_path(const std::string& path,
                           const std::function<void(const std::string& tmp_path)>& writer);

/// A temporary file's path for a scope: the file is removed when the TempFile is destroyed
/// (every exit path, exceptions included) unless released, and by the signal handler while it
/// exists (core/signal_cleanup.hpp). Nothing is created: the owner writes the file.
class TempFile {
 public:
  explicit TempFile(std::string path);
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }
  /// Keeps the file (e.g. after renaming it to the output): no longer removed.
  void release();

 private:
  std::string path_;
  SignalCleanup on_signal_;
};

/// Reads a whole file ("-": standard input, core/standard_input.hpp) and records it as an input
/// (path_guard); throws InputError naming the path for a directory, a file it cannot open or a
/// read that fails (never std::ios_base::failure).
std::string read_text_file(const std::string& path);

}  // namespace quadapt
