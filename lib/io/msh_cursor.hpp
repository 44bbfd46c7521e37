#pragma once
// Internal to lib/io: a cursor over a whole MSH file held in memory, reading ASCII tokens and
// binary values, with error messages "PATH: $Section: problem". Not a public API.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace quadapt::msh_detail {

class Cursor {
 public:
  Cursor(const std::string& buf, std::string path)
      : p_(buf.data()), end_(buf.data() + buf.size()), path_(std::move(path)) {}

  std::string section;     ///< current section name (without '$'), for messages
  bool binary = false;     ///< file-type 1
  bool swap = false;       ///< binary data of the other endianness
  int size_bytes = 8;      ///< data-size of the header (size of size_t in MSH 4.1 binary)

  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_, section.empty() ? problem : "$" + section + ": " + problem);
  }
  [[noreturn]] void truncated(std::string_view what) const {
    fail("truncated file (end of file while reading " + std::string(what) + ")");
  }

  /// Skips whitespace; true at end of file.
  bool at_end() {
    skip_ws();
    return p_ >= end_;
  }

  /// Next whitespace-delimited token.
  std::string_view token(std::string_view what) {
    skip_ws();
    if (p_ >= end_) truncated(what);
    const char* s = p_;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    return {s, static_cast<size_t>(p_ - s)};
  }

  long long integer(std::string_view what) {
    std::string_view t = token(what);
    long long v = 0;
    const char* b = t.data();
    if (!t.empty() && *b == '+') ++b;
    auto [q, ec] = std::from_chars(b, t.data() + t.size(), v);
    if (ec != std::errc() || q != t.data() + t.size())
      fail("expected an integer (" + std::string(what) + "), found '" + clip(t) + "'");
    return v;
  }

  /// A count: a non-negative integer no larger than `max`.
  long long count(std::string_view what, long long max = (1LL << 40)) {
    long long v = integer(what);
    if (v < 0 || v > max) fail("invalid " + std::string(what) + " " + std::to_string(v));
    return v;
  }

  double real(std::string_view what) {
    std::string_view t = token(what);
    double v = 0;
    const char* b = t.data();
    if (!t.empty() && *b == '+') ++b;
    auto [q, ec] = std::from_chars(b, t.data() + t.size(), v);
    if (ec == std::errc::result_out_of_range) {
      v = std::strtod(std::string(t).c_str(), nullptr);  // denormals / overflow: as strtod does
    } else if (ec != std::errc() || q != t.data() + t.size()) {
      fail("expected a number (" + std::string(what) + "), found '" + clip(t) + "'");
    }
    return v;
  }

  /// The rest of the current line (after leading blanks and newlines), trimmed.
  std::string line(std::string_view what) {
    skip_ws();
    if (p_ >= end_) truncated(what);
    const char* s = p_;
    while (p_ < end_ && *p_ != '\n') ++p_;
    std::string_view t(s, static_cast<size_t>(p_ - s));
    while (!t.empty() && is_space(t.back())) t.remove_suffix(1);
    return std::string(t);
  }

  /// The rest of the current line, as line(), where a quoted string loses its quotes.
  std::string quoted(std::string_view what) {
    const std::string l = line(what);
    const size_t q1 = l.find('"');
    if (q1 == std::string::npos) return l;
    const size_t q2 = l.find('"', q1 + 1);
    return l.substr(q1 + 1, q2 == std::string::npos ? std::string::npos : q2 - q1 - 1);
  }

  /// True when the next token is `word` (nothing read). Safe between binary blocks too: their
  /// first bytes (a small integer) are neither blanks nor '$'.
  bool next_is(std::string_view word) const {
    const char* q = p_;
    while (q < end_ && is_space(*q)) ++q;
    if (static_cast<size_t>(end_ - q) < word.size() || std::string_view(q, word.size()) != word) return false;
    q += word.size();
    return q == end_ || is_space(*q);
  }

  /// Reads "$EndNAME".
  void expect_end(const std::string& name) {
    const std::string want = "$End" + name;
    std::string_view t = token(want);
    if (t != want)
      fail("expected " + want + ", found '" + clip(t) + "' (wrong counts or malformed section)");
  }

  /// Skips to just after "$EndNAME" (unknown sections).
  void skip_section(const std::string& name) {
    const std::string want = "$End" + name;
    std::string_view rest(p_, static_cast<size_t>(end_ - p_));
    size_t at = rest.find(want);
    if (at == std::string_view::npos) fail("section has no " + want + " (truncated file?)");
    p_ += at + want.size();
  }

  /// Before binary data that follows an ASCII line: consumes the rest of that line and its
  /// newline (never more: binary bytes may look like whitespace).
  void begin_binary() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r')) ++p_;
    if (p_ < end_ && *p_ == '\n') ++p_;
  }

  template <class T>
  T bin(std::string_view what) {
    if (static_cast<size_t>(end_ - p_) < sizeof(T)) truncated(what);
    T v;
    std::memcpy(&v, p_, sizeof(T));
    p_ += sizeof(T);
    if (swap) {
      char* c = reinterpret_cast<char*>(&v);
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(c[i], c[sizeof(T) - 1 - i]);
    }
    return v;
  }
  long long bin_int(std::string_view what) { return bin<std::int32_t>(what); }
  long long bin_size(std::string_view what) {
    return size_bytes == 8 ? static_cast<long long>(bin<std::uint64_t>(what))
                           : static_cast<long long>(bin<std::uint32_t>(what));
  }
  double bin_double(std::string_view what) { return bin<double>(what); }

  /// ASCII or binary, following `binary`.
  long long any_int(std::string_view what) { return binary ? bin_int(what) : integer(what); }
  long long any_size(std::string_view what) { return binary ? bin_size(what) : integer(what); }
  double any_real(std::string_view what) { return binary ? bin_double(what) : real(what); }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v'; }
  void skip_ws() {
    while (p_ < end_ && is_space(*p_)) ++p_;
  }
  static std::string clip(std::string_view t) {
    std::string s(t.substr(0, 40));
    for (char& c : s)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return s;
  }

  const char* p_;
  const char* end_;
  std::string path_;
};

}  // namespace quadapt::msh_detail
