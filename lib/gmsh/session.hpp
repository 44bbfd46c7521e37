#pragma once
// The one adapter around the Gmsh SDK (gmsh.h, API 4.8): initialisation by RAII and a call
// wrapper that turns Gmsh failures into quadapt::ExternalError. Every use of the SDK in
// quadapt goes through these two (see docs/design.md §6 for the SDK's quirks).
//
//   GmshSession gmsh;                                   // initialise (nested sessions share it)
//   gmsh_call("open " + path, [&] { gmsh::open(path); });
//
// Not thread-safe: Gmsh has one global state; use it from one thread.
#include <functional>
#include <string>

namespace quadapt {

/// Keeps the Gmsh SDK initialised while alive. Sessions nest through a reference count: the
/// first one initialises Gmsh (no configuration files, General.Terminal = 0 unless `verbose`,
/// General.AbortOnError = 0 so that errors inside Gmsh's OpenMP regions do not terminate the
/// process), the last one finalizes it. The outermost session starts from an empty model and
/// no views; nested sessions share the current model (call gmsh::clear() to start afresh).
class GmshSession {
 public:
  explicit GmshSession(bool verbose = false);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

/// Runs `body` (calls of gmsh:: functions) and reports failure as
/// ExternalError("Gmsh: WHAT: message"): Gmsh 4.8 throws std::string, and with
/// AbortOnError = 0 some failures are only logged as "Error: ..." (collected with
/// gmsh::logger while body runs). quadapt errors thrown by body pass through unchanged.
/// Requires a live GmshSession.
void gmsh_call(const std::string& what, const std::function<void()>& body);

}  // namespace quadapt
