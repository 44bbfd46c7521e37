#pragma once
// SHA-256 (FIPS 180-4) of a byte string or a file, as 64 lowercase hex digits: the input
// checksums of the tools' reports (cli/provenance.hpp). No external crypto library.
#include <cstddef>
#include <cstdint>
#include <string>

namespace quadapt {

/// Incremental SHA-256.
class Sha256 {
 public:
  Sha256();
  void update(const void* data, size_t n);
  /// Finishes and returns the digest as 64 hex digits (the object is spent afterwards).
  std::string hex();

 private:
  void block(const unsigned char* p);
  uint32_t h_[8];
  unsigned char buf_[64];
  size_t fill_ = 0;
  uint64_t bytes_ = 0;
};

/// SHA-256 of `s`.
std::string sha256_hex(const std::string& s);
/// SHA-256 of the file's bytes; throws InputError("path: cannot read ...") if it cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace quadapt
