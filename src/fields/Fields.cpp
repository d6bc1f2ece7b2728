#include "fields/Fields.hpp"

#include "core/Error.hpp"

namespace gf {

Field::Field(DM dm, const char* name) {
  GF_PETSC(DMCreateGlobalVector(dm, &v_));
  GF_PETSC(PetscObjectSetName(reinterpret_cast<PetscObject>(v_), name));
  GF_PETSC(VecSet(v_, 0.0));
}

Field::~Field() {
  if (v_) VecDestroy(&v_);
}

Field& Field::operator=(Field&& o) noexcept {
  if (this != &o) {
    if (v_) VecDestroy(&v_);
    v_ = o.v_;
    o.v_ = nullptr;
  }
  return *this;
}

State::State(const Grid& g)
    : phi(g.dm_cell(), "phi"),
      frac(g.dm_cell(), "volume_fraction"),
      vel(g.dm_vel(), "velocity"),
      vel_old(g.dm_vel(), "velocity_old"),
      p(g.dm_cell(), "p"),
      S(g.dm_ten(), "S"),
      S_node(g.dm_node(), "S_node"),
      s_wall(g.dm_vel(), "s_wall"),
      vel_pred(g.dm_vel(), "velocity_prediction"),
      s_side(g.dm_vel(), "s_side"),
      rho(g.dm_cell(), "rho"),
      eta(g.dm_cell(), "eta") {}

}  // namespace gf
