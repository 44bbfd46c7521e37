#pragma once
// The one adapter around the Gmsh SDK (gmsh.h, API 4.8): initialisation by RAII and a call
// wrapper that turns Gmsh failures into quadapt::ExternalError. Every use of the SDK in
// quadapt goes through lib/gmsh (these and gmsh/gmsh_recombine.hpp; docs/design.md §6 for the SDK's
// quirks); the SDK headers are private to the library.
//
//   GmshSession gmsh;                                   // initialise (nested sessions share it)
//   gmsh_call("open " + path, [&] { gmsh::open(path); });
//
// Not thread-safe: Gmsh has one global state; use it from one thread.
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace quadapt {

/// Keeps the Gmsh SDK initialised while alive. Sessions nest through a reference count: the
/// first one initialises Gmsh (no configuration files, General.Terminal = 0 unless `verbose`,
/// General.AbortOnError = 0 so that errors inside Gmsh's OpenMP regions do not terminate the
/// process), the last one finalizes it. quadapt's calls work in models of their own
/// ("quadapt-geometry", "quadapt-recombine"), which they remove when done.
///
/// A program that uses Gmsh itself and had initialised it before: the first session then borrows
/// that Gmsh — no initialize, no finalize — and the last one gives back the caller's current
/// model and its General.Terminal and General.AbortOnError; the caller's models, views and other
/// options are left as they were (tests/unit/gmsh/test_gmsh.cpp). Do not finalize Gmsh while a
/// quadapt object that holds a session (open_geometry's) is alive.
class GmshSession {
 public:
  explicit GmshSession(bool verbose = false);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

/// Removes the model `name` if Gmsh has one (quadapt's own models, on success and on failure: a
/// caller's own Gmsh keeps its models only); never throws. Requires a live session.
void remove_gmsh_model(const std::string& name) noexcept;

/// remove_gmsh_model(name) when it goes out of scope, however the scope ends: declare it after the
/// GmshSession and before the gmsh_call that adds the model.
class GmshModelScope {
 public:
  explicit GmshModelScope(std::string name) : name_(std::move(name)) {}
  ~GmshModelScope() { remove_gmsh_model(name_); }
  GmshModelScope(const GmshModelScope&) = delete;
  GmshModelScope& operator=(const GmshModelScope&) = delete;
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

/// Sets Gmsh's global numeric options while alive and restores the values it found (Gmsh's
/// options are process-wide: a caller's settings survive our calls). Requires a live session.
class GmshOptionGuard {
 public:
  explicit GmshOptionGuard(std::vector<std::pair<std::string, double>> options);
  ~GmshOptionGuard();
  GmshOptionGuard(const GmshOptionGuard&) = delete;
  GmshOptionGuard& operator=(const GmshOptionGuard&) = delete;

 private:
  std::vector<std::pair<std::string, double>> saved_;
};

/// Runs `body` (calls of gmsh:: functions) and reports failure as
/// ExternalError("Gmsh: WHAT: message"): Gmsh 4.8 throws std::string, and with
/// AbortOnError = 0 some failures are only logged as "Error: ..." (collected with
/// gmsh::logger while body runs). quadapt errors thrown by body pass through unchanged.
/// Requires a live GmshSession.
void gmsh_call(const std::string& what, const std::function<void()>& body);

}  // namespace quadapt
