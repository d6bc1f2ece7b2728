#include "operators/Operators.hpp"

namespace gf::ops {

void convection(const Box& b, const Vel* const* vel, Vel** out) {
  const double hx = b.hx, hy = b.hy;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      // x-momentum on face (i, j): d(uu)/dx between cell centres i-1 and i, d(uv)/dy between
      // the nodes (i, j) and (i, j+1). At wall nodes v = 0, so the uv flux vanishes.
      if (i == 0) {
        out[j][i].u = 0.0;
      } else {
        const double uc_r = 0.5 * (vel[j][i].u + vel[j][i + 1].u);
        const double uc_l = 0.5 * (vel[j][i - 1].u + vel[j][i].u);
        double fy_t = 0.0, fy_b = 0.0;
        if (j + 1 < b.ny)
          fy_t = 0.25 * (vel[j][i].u + vel[j + 1][i].u) * (vel[j + 1][i - 1].v + vel[j + 1][i].v);
        if (j > 0)
          fy_b = 0.25 * (vel[j - 1][i].u + vel[j][i].u) * (vel[j][i - 1].v + vel[j][i].v);
        out[j][i].u = (uc_r * uc_r - uc_l * uc_l) / hx + (fy_t - fy_b) / hy;
      }
      // y-momentum on face (i, j): d(uv)/dx between nodes (i, j) and (i+1, j), d(vv)/dy between
      // cell centres j-1 and j.
      if (j == 0) {
        out[j][i].v = 0.0;
      } else {
        const double vc_t = 0.5 * (vel[j][i].v + vel[j + 1][i].v);
        const double vc_b = 0.5 * (vel[j - 1][i].v + vel[j][i].v);
        double fx_r = 0.0, fx_l = 0.0;
        if (i + 1 < b.nx)
          fx_r = 0.25 * (vel[j - 1][i + 1].u + vel[j][i + 1].u) * (vel[j][i].v + vel[j][i + 1].v);
        if (i > 0)
          fx_l = 0.25 * (vel[j - 1][i].u + vel[j][i].u) * (vel[j][i - 1].v + vel[j][i].v);
        out[j][i].v = (fx_r - fx_l) / hx + (vc_t * vc_t - vc_b * vc_b) / hy;
      }
    }
}

void divergence(const Box& b, const Vel* const* vel, PetscScalar** div) {
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      div[j][i] = (vel[j][i + 1].u - vel[j][i].u) / b.hx + (vel[j + 1][i].v - vel[j][i].v) / b.hy;
}

}  // namespace gf::ops
