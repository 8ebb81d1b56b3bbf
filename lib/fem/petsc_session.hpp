#pragma once
// RAII PETSc (and MPI) initialisation for the commands and tests that use the FEM solver.
// Only those initialise MPI: the texture and water commands stay plain serial programs.
#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace wr {

// A PETSc call that failed: its code (PETSC_ERR_*) and PETSc's one-line text for it.
class PetscFailure : public std::runtime_error {
 public:
  PetscFailure(PetscErrorCode code, const std::string& what) : std::runtime_error(what), code_(code) {}
  PetscErrorCode code() const { return code_; }
  // An option value PETSc does not know (a misspelt -ksp_type, a bad argument): the user's
  // --petsc options, not the solver, are at fault.
  bool bad_option() const {
    return code_ == PETSC_ERR_ARG_WRONG || code_ == PETSC_ERR_ARG_OUTOFRANGE ||
           code_ == PETSC_ERR_ARG_UNKNOWN_TYPE || code_ == PETSC_ERR_ARG_INCOMP;
  }

 private:
  PetscErrorCode code_;
};

namespace petsc {
// PETSc calls return error codes; this turns them into exceptions naming the call.
inline void check(PetscErrorCode ierr, const char* what) {
  if (!ierr) return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  throw PetscFailure(ierr, std::string("PETSc failed in ") + what + (text ? std::string(": ") + text : std::string()) +
                             " (code " + std::to_string(ierr) + ")");
}
}  // namespace petsc

class PetscSession {
 public:
  PetscSession(int* argc, char*** argv) {
    if (PetscInitialize(argc, argv, nullptr, nullptr) != 0) throw std::runtime_error("PetscInitialize failed");
    // Errors come back as codes that petsc::check turns into one-line exceptions; PETSc's own
    // multi-line trace on stderr would bury that line.
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  }
  ~PetscSession() { PetscFinalize(); }
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
};

}  // namespace wr
