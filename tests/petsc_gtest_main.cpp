// main() of the tests that need PETSc (and MPI) started: GoogleTest inside a PetscSession.
#include <gtest/gtest.h>

#include "lib/fem/petsc_session.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  wr::PetscSession petsc(&argc, &argv);
  return RUN_ALL_TESTS();
}
