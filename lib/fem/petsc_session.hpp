#pragma once
// RAII PETSc (and MPI) initialisation for the commands and tests that use the FEM solver.
// Only those initialise MPI: the texture and water commands stay plain serial programs.
#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace wr {

namespace petsc {
// PETSc calls return error codes; this turns them into exceptions naming the call.
inline void check(PetscErrorCode ierr, const char* what) {
  if (ierr) throw std::runtime_error(std::string("PETSc failed in ") + what + " (code " + std::to_string(ierr) + ")");
}
}  // namespace petsc

class PetscSession {
 public:
  PetscSession(int* argc, char*** argv) {
    if (PetscInitialize(argc, argv, nullptr, nullptr) != 0) throw std::runtime_error("PetscInitialize failed");
  }
  ~PetscSession() { PetscFinalize(); }
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
};

}  // namespace wr
