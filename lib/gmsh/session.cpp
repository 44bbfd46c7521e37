#include "gmsh/session.hpp"

#include <gmsh.h>

#include <algorithm>

#include "core/error.hpp"

namespace quadapt {

namespace {
int g_sessions = 0;    // live GmshSession objects
int g_call_depth = 0;  // nested gmsh_call
// The program that calls quadapt had initialised Gmsh itself: quadapt neither initialises nor
// finalizes it, and gives back the caller's current model and the options it set (finalize wiped
// the caller's models and options: a library user's review, session 38).
bool g_borrowed = false;
std::string g_caller_model;
std::vector<std::pair<std::string, double>> g_caller_options;
const char* const kSessionOptions[] = {"General.Terminal", "General.AbortOnError"};

// Gmsh 4.8 has no isInitialized(); an initialised Gmsh always has a model (gmsh::clear() and
// model::remove() leave an empty one), an uninitialised one lists none.
bool gmsh_initialised() {
  std::vector<std::string> names;
  try {
    gmsh::model::list(names);
  } catch (...) {
    return false;
  }
  return !names.empty();
}
}  // namespace

GmshSession::GmshSession(bool verbose) {
  if (g_sessions == 0) {
    try {
      g_borrowed = gmsh_initialised();
      if (g_borrowed) {
        gmsh::model::getCurrent(g_caller_model);
        g_caller_options.clear();
        for (const char* o : kSessionOptions) {
          double v = 0;
          gmsh::option::getNumber(o, v);
          g_caller_options.emplace_back(o, v);
        }
      } else {
        gmsh::initialize(0, nullptr, false);
      }
      gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
      gmsh::option::setNumber("General.AbortOnError", 0);
    } catch (const std::string& s) {
      throw ExternalError("Gmsh: initialisation failed: " + s);
    }
  }
  ++g_sessions;
}

GmshSession::~GmshSession() {
  if (--g_sessions == 0) {
    try {
      if (g_borrowed) {
        for (const auto& [o, v] : g_caller_options) gmsh::option::setNumber(o, v);
        gmsh::model::setCurrent(g_caller_model);
      } else {
        gmsh::finalize();
      }
    } catch (...) {
    }
  }
}

void remove_gmsh_model(const std::string& name) noexcept {
  try {
    std::vector<std::string> names;
    gmsh::model::list(names);
    if (std::find(names.begin(), names.end(), name) == names.end()) return;
    gmsh::model::setCurrent(name);
    gmsh::model::remove();
  } catch (...) {
  }
}

GmshOptionGuard::GmshOptionGuard(std::vector<std::pair<std::string, double>> options) {
  for (auto& [name, value] : options) {
    double old = 0;
    gmsh::option::getNumber(name, old);
    saved_.emplace_back(name, old);
    gmsh::option::setNumber(name, value);
  }
}

GmshOptionGuard::~GmshOptionGuard() {
  for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
    try {
      gmsh::option::setNumber(it->first, it->second);
    } catch (...) {
    }
  }
}

void gmsh_call(const std::string& what, const std::function<void()>& body) {
  if (g_sessions == 0) throw Error("gmsh_call(" + what + ") without a GmshSession");
  const bool outer = g_call_depth == 0;
  if (outer) gmsh::logger::start();
  ++g_call_depth;
  auto finish = [&]() -> std::string {
    --g_call_depth;
    if (!outer) return "";
    std::vector<std::string> log;
    try {
      gmsh::logger::get(log);
      gmsh::logger::stop();
    } catch (...) {
    }
    for (const std::string& line : log)
      if (line.rfind("Error", 0) == 0) return line;
    return "";
  };
  try {
    body();
  } catch (const Error&) {
    finish();
    throw;
  } catch (const std::string& s) {
    std::string logged = finish();
    throw ExternalError("Gmsh: " + what + ": " + (s.empty() ? logged : s));
  } catch (const std::exception& e) {
    finish();
    throw ExternalError("Gmsh: " + what + ": " + e.what());
  }
  std::string logged = finish();
  if (!logged.empty()) throw ExternalError("Gmsh: " + what + ": " + logged);
}

}  // namespace quadapt
