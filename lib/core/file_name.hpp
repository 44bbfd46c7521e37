#pragma once
// File-name conventions shared by every tool: a file's kind is read from its extension, compared
// without regard to case (sol.MSH is a mesh like sol.msh, pic.PNG a picture like pic.png).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace quadapt {

/// The extension of `path` with its dot, lower-cased: "dir/Sol.MSH" -> ".msh"; "" when none.
inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace quadapt
