#pragma once
// `wetroad bench fem-operator`: the block's stiffness product, assembled (PETSc AIJ) against
// matrix-free (lib/fem/matrix_free_stiffness.hpp), on the thesis scene's mesh (a size x size face
// of 30 mm at each refinement, a cube, the default grading): their difference, the time of one
// product (best of `repeats`), and the memory each holds. MPI: run under mpirun; rank 0 reports.
#include <vector>

#include <nlohmann/json.hpp>

namespace wr::bench {

nlohmann::json fem_operator(int size, const std::vector<int>& refines, int repeats);

}  // namespace wr::bench
