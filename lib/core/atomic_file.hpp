#pragma once
// Atomic output: write to a temporary file beside the target, then rename over it, so that a
// reader (or an interrupted Makefile loop) never sees a half-written file.
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace quadapt {

/// Writes `path` atomically: `writer` fills a stream on "path.tmp-PID", which is renamed to
/// `path` only if writer returns normally and the stream is good. On any exception the
/// temporary is removed and the exception propagates. Throws ExternalError on I/O failure.
void atomic_write(const std::string& path, const std::function<void(std::ostream&)>& writer,
                  bool binary = false);

/// Same, for writers that need a file name (e.g. the Gmsh SDK or an external program): `writer`
/// receives the temporary path to create; it is renamed to `path` afterwards.
void atomic_write_via_path(const std::string& path,
                           const std::function<void(const std::string& tmp_path)>& writer);

/// Throws InputError if `output` names the same file as one of `inputs` (never overwrite an
/// input). Compares canonical paths when the files exist, else lexically normalised paths.
void check_not_an_input(const std::string& output, const std::vector<std::string>& inputs);

/// Reads a whole text file; throws InputError("path: cannot open ...") if it cannot.
std::string read_text_file(const std::string& path);

}  // namespace quadapt
