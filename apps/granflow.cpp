#include <petscsys.h>
#include "grid/Grid.hpp"
#include "fields/Fields.hpp"
int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  {
    gf::Grid g(PETSC_COMM_WORLD, 64, 16, 0.8, 0.2);
    gf::State s(g);
    PetscPrintf(PETSC_COMM_WORLD, "grid %d x %d h=%g\n", (int)g.nx(), (int)g.ny(), g.hx());
  }
  PetscCall(PetscFinalize());
  return 0;
}
