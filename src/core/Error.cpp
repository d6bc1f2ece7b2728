#include "core/Error.hpp"

#include <petscsys.h>

#include <cstring>

namespace gf {

namespace {

// The message of the error being raised: PETSc calls the handler once per level of the
// call stack (PETSC_ERROR_INITIAL first, then PETSC_ERROR_REPEAT on the way up); the first
// one says what went wrong, the others only where.
struct Captured {
  int code = 0;
  std::string message;
};
Captured g_captured;

PetscErrorCode capture_handler(MPI_Comm, int, const char*, const char*, PetscErrorCode n,
                               PetscErrorType p, const char* mess, void*) {
  if (p == PETSC_ERROR_INITIAL) {
    g_captured.code = static_cast<int>(n);
    g_captured.message = mess ? mess : "";
  }
  return n;
}

// One line: PETSc messages may end with a newline or hold several lines.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

bool PetscFailure::user_input_kind() const {
  return code_ == PETSC_ERR_ARG_UNKNOWN_TYPE || code_ == PETSC_ERR_USER_INPUT ||
         code_ == PETSC_ERR_ARG_OUTOFRANGE || code_ == PETSC_ERR_MISSING_FACTOR ||
         code_ == PETSC_ERR_ARG_WRONG || code_ == PETSC_ERR_ARG_INCOMP;
}

void throw_petsc_failure(int code, const char* call, const char* file, int line) {
  const char* generic = nullptr;
  PetscErrorMessage(static_cast<PetscErrorCode>(code), &generic, nullptr);
  std::string what = "PETSc error " + std::to_string(code);
  if (generic) what += " (" + one_line(generic) + ")";
  if (g_captured.code == code && !g_captured.message.empty())
    what += ": " + one_line(g_captured.message);
  g_captured = {};
  // The file relative to the source tree: the path of the build machine says nothing.
  const char* src = std::strstr(file, "src/");
  what += std::string(" [in ") + call + " at " + (src ? src : file) + ":" + std::to_string(line) +
          "]";
  throw PetscFailure(code, what);
}

void install_petsc_error_capture() { PetscPushErrorHandler(capture_handler, nullptr); }

std::vector<std::string> unused_petsc_options() {
  // Read by PetscFinalize (or PETSc's own bookkeeping), never before it.
  static const char* const kAtExit[] = {"log_view", "log_summary", "options_left", "malloc_dump",
                                        "memory_view", "objects_dump", "log_trace",
                                        "options_view", "history"};
  std::vector<std::string> out;
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  if (PetscOptionsLeftGet(nullptr, &n, &names, &values)) return out;
  for (PetscInt k = 0; k < n; ++k) {
    const std::string name = names[k] ? names[k] : "";
    bool at_exit = false;
    for (const char* e : kAtExit) at_exit = at_exit || name.rfind(e, 0) == 0;
    if (at_exit) continue;
    std::string o = "-" + name;
    if (values[k] && *values[k]) o += std::string(" ") + values[k];
    out.push_back(o);
  }
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  return out;
}

}  // namespace gf
