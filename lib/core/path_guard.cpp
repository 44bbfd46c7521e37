#include "core/path_guard.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <mutex>
#include <optional>
#include <vector>

#include "core/error.hpp"

namespace quadapt {

namespace {

struct FileId {
  dev_t dev;
  ino_t ino;
  bool operator==(const FileId& o) const { return dev == o.dev && ino == o.ino; }
};

std::optional<FileId> file_id(const std::string& path) {
  if (path.empty() || path == "-") return std::nullopt;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;  // follows symlinks
  return FileId{st.st_dev, st.st_ino};
}

struct Entry {
  std::string path;
  FileId id;
};

struct Output {
  std::string path, role, remedy;  // role, remedy: how a refusal names it and what to do instead
};

struct Registry {
  std::mutex mutex;
  bool enabled = false;
  std::vector<Entry> inputs;
  std::vector<Output> outputs;  // may not exist yet: identity taken when an input is added
};

Registry& registry() {
  static Registry r;
  return r;
}

[[noreturn]] void refuse(const std::string& output, const std::string& input, const std::string& role = "",
                         const std::string& remedy = "") {
  throw InputError(output, (role.empty() ? std::string("output") : role) + " would overwrite the input file " + input +
                               "; " + (remedy.empty() ? std::string("choose another output path") : remedy));
}

// The path with every symlink of its existing part resolved (names a file that may not exist yet).
std::string canonical_key(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  return ec ? path : p.string();
}

// Caller holds the lock.
void check_locked(Registry& r, const std::string& output, const std::string& role = "",
                  const std::string& remedy = "") {
  const auto id = file_id(output);
  if (!id) return;  // a file that does not exist cannot be an input
  for (const Entry& e : r.inputs)
    if (e.id == *id) refuse(output, e.path, role, remedy);
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  const auto ia = file_id(a);
  const auto ib = file_id(b);
  return ia && ib && *ia == *ib;
}

void enable_input_guard(bool on) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.enabled = on;
}

void protect_input(const std::string& path) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.enabled) return;
  const auto id = file_id(path);
  if (!id) return;
  for (const Output& out : r.outputs)
    if (file_id(out.path) == id) refuse(out.path, path, out.role, out.remedy);
  for (const Entry& e : r.inputs)
    if (e.id == *id) return;
  r.inputs.push_back({path, *id});
}

void protect_output(const std::string& path, const std::string& role, const std::string& remedy) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.enabled) return;
  check_locked(r, path, role, remedy);
  if (path != "-") {
    const std::string key = canonical_key(path);
    for (const Output& out : r.outputs)
      if (out.path != "-" && canonical_key(out.path) == key) {
        if (out.role.empty()) throw InputError(path, "is given twice as an output (also as " + out.path + ")");
        // an output the user did not name (a .opt beside a mesh): say which, not "given twice"
        throw InputError(path, (role.empty() ? std::string("this output") : role) + " is " + out.role + " too; " +
                                   (remedy.empty() ? std::string("choose another output path") : remedy));
      }
  }
  r.outputs.push_back({path, role, remedy});
}

void check_not_an_input(const std::string& path) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.enabled) return;
  check_locked(r, path);
}

void clear_protected_paths() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.inputs.clear();
  r.outputs.clear();
}

}  // namespace quadapt
