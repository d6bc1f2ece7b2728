#pragma once
// Prescribed velocity fields and initial shapes for verifying the level-set module (section 3.1)
// on the classical benchmarks: Zalesak's slotted disk in solid-body rotation and the single
// vortex of LeVeque (1996) / Rider & Kothe (1998).
//
// Velocities are built from a stream function psi sampled at the grid NODES,
//   u(left face of (i, j))   =  (psi(i, j+1) - psi(i, j)) / hy,
//   v(bottom face of (i, j)) = -(psi(i+1, j) - psi(i, j)) / hx,
// so that the discrete divergence of every cell is zero to round-off (the four node values
// cancel), which is what a projected velocity (eq. 28) provides the transport scheme. psi is
// constant along the walls, so the wall normal velocity (eq. 20) is zero as well; the wall faces
// are also set to exactly 0 as the grid convention requires.
#include <petscdmda.h>
#include <petscvec.h>

#include "core/Error.hpp"
#include "grid/Grid.hpp"

namespace gf::levelset {

// Face velocities of the global dm_vel Vec vel from psi(x, y) (m^2/s) sampled at the nodes, as
// above: divergence free to round-off in every cell; the wall faces (u at i = 0 unless x is
// periodic, v at j = 0) are set to exactly 0. With periodic x, psi must be periodic in x for
// the face nx (= face 0) to see the same velocity from both sides.
template <class Psi>
void velocity_from_stream_function(const Grid& g, Vec vel, const Psi& psi) {
  const Box& b = g.box();
  Vel** v;
  GF_PETSC(DMDAVecGetArray(g.dm_vel(), vel, &v));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double p00 = psi(b.xf(i), b.yf(j));
      v[j][i].u = b.wall_u(i) ? 0.0 : (psi(b.xf(i), b.yf(j + 1)) - p00) / b.hy;
      v[j][i].v = j == 0 ? 0.0 : -(psi(b.xf(i + 1), b.yf(j)) - p00) / b.hx;
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_vel(), vel, &v));
}

// (a) Solid-body rotation about (cx, cy) with angular velocity omega (rad/s, counter-clockwise
// for omega > 0) for distances r <= r_solid from the centre, brought smoothly (C1 in the
// velocity) to rest at r >= r_still so that psi is constant on the walls when r_still is at most
// the distance from the centre to the nearest wall.
void rotation_velocity(const Grid& g, Vec vel, double omega, double cx, double cy,
                       double r_solid, double r_still);
// Same with r_still = distance to the nearest wall and r_solid = 0.85 r_still (for Zalesak's
// disk in the unit square: exact rotation up to r = 0.425, beyond the disk's 0.4).
void rotation_velocity(const Grid& g, Vec vel, double omega, double cx, double cy);

// (b) Single vortex in the unit square (the grid must be 1 m x 1 m):
//   psi = sin^2(pi x) sin^2(pi y) / pi * cos(pi t / T),
// u = d(psi)/dy, v = -d(psi)/dx; the flow reverses at t = T/2 and at t = T every fluid particle
// is back where it started.
void single_vortex_velocity(const Grid& g, Vec vel, double t, double T);

// Exact signed distances (m), negative inside the shape (the granular phase).
double circle_distance(double x, double y, double cx, double cy, double r);
// Zalesak's disk: disk of radius r centred (cx, cy) with a slot of width slot_width cut upwards
// from the bottom of the disk over a depth slot_depth.
double zalesak_distance(double x, double y, double cx, double cy, double r, double slot_width,
                        double slot_depth);
double rectangle_distance(double x, double y, double x0, double x1, double y0, double y1);

// Initial level sets at the cell centres of the global Vec phi (dm_cell). With periodic x the
// shape is repeated with period Lx (the distance to the nearest image).
void init_circle(const Grid& g, Vec phi, double cx, double cy, double r);
void init_zalesak(const Grid& g, Vec phi, double cx, double cy, double r, double slot_width,
                  double slot_depth);
void init_rectangle(const Grid& g, Vec phi, double x0, double x1, double y0, double y1);
void init_layer(const Grid& g, Vec phi, double height);
// A pile on the bottom wall: the trapezoid with base [x0, x1] on y = 0, height h and both sides
// at slope_deg to the horizontal; phi is the distance to its free sides (the two slopes and the
// top), negative inside. The base lies on the wall and is not an interface.
double trapezoid_distance(double x, double y, double x0, double x1, double h, double slope_deg);
void init_trapezoid(const Grid& g, Vec phi, double x0, double x1, double h, double slope_deg);  // phi = y - height

}  // namespace gf::levelset
