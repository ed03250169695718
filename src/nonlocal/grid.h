/* grid.h: the unit grid of the element fluidity in 2 or 3 dimensions, its
 * ghost rules and Laplacian (MODEL.md section 5 step 2, [DK-silo] §5.2 (ii),
 * eq. 5.1), written once for D = 2 (the 5-point stencil) and D = 3 (the
 * 7-point one).
 *
 * Units are boxes of h_0 x h_1 (x h_2) on n_0 x n_1 (x n_2) cells, unit
 * (c_0, c_1, c_2) stored at e = c_0 + n_0 (c_1 + n_1 c_2) (n_2 = 1, c_2 = 0
 * in 2D). A unit has 2D faces, face f = 2a + s on axis a = f/2 towards
 * -1 (s = 0) or +1 (s = 1): in 2D the W, E, S, N sides, in the order of the
 * mesh edges left, right, bottom, top; in 3D then the bottom and top along z.
 *
 *   lap_e = sum_a (g_{a+} - 2 g_e + g_{a-}) / h_a^2
 * (the terms added in axis order, the first taken as it is), where g_{a+-}
 * is the filled neighbour's g across that face or a ghost value:
 *   empty neighbour, Neumann face (free, frictionless, symmetry) or the open
 *     part of an outlet face:  g_ghost = g_e (d_n g = 0 at the face);
 *   Dirichlet face (no slip):  g_ghost = -g_e (g = 0 at the face, midway);
 *   periodic face:             the unit on the opposite side (wrap).
 * Empty units have lap_e = 0. A unit is filled when its dense mass
 * sm_e > 0 (the caller's flags as 1 or 0 do as well).
 *
 * The backward-Euler row of the same operator (implicit.h), for unit e with
 * coefficient c and w_f = 1/h_{f/2}^2:
 *   diagonal  1 + c sum_{f: neighbour} w_f + c sum_{f: ghost k g_e} (1 - k) w_f
 *   neighbour -c w_f
 * in face order (a periodic axis of two units gives one neighbour twice;
 * a unit that is its own neighbour, a periodic axis of one unit, adds
 * nothing). One side rule (mpm_nonlocal_grid_side) serves the stencil and
 * the row, so the explicit and the implicit schemes see the same ghosts. */
#ifndef MPM_NONLOCAL_GRID_H
#define MPM_NONLOCAL_GRID_H

#include <stddef.h>

#include "core/error.h"

/* Ghost rule of one face of the grid (a mesh edge in 2D). */
enum mpm_nonlocal_ghost {
  MPM_GHOST_NEUMANN = 0,    /* g_ghost = g_e */
  MPM_GHOST_DIRICHLET,      /* g_ghost = -g_e (g = 0 on the face) */
  MPM_GHOST_PERIODIC        /* wrap to the opposite side */
};

/* Largest number of faces of a unit (3D). */
#define MPM_NONLOCAL_FACES 6

typedef struct mpm_nonlocal_grid {
  int dim;                    /* 2 or 3 */
  int n[3];                   /* units along each axis (n[2] = 1 in 2D) */
  size_t stride[3];           /* 1, n_0, n_0 n_1: index step along each axis */
  size_t nu;                  /* units n_0 n_1 n_2 */
  double ih2[3];              /* 1/h_a^2 [1/m^2] (1/dx^2, 1/dy^2, 1/dz^2) */
  int ghost[MPM_NONLOCAL_FACES];  /* faces -x, +x, -y, +y, -z, +z: enum mpm_nonlocal_ghost */
  int open_face;              /* face with an open outlet, -1: none ... */
  int open_lo[3], open_hi[3]; /* ... whose units with open_lo[b] <= c_b < open_hi[b] on
                                 every axis b along it have a Neumann face there ... */
  const unsigned char *open_mask;  /* ... and, when not NULL, open_mask[e] = 1 (a disc's
                                      faces within that range); not owned */
  unsigned stamp;             /* changes whenever the ghost rules do */
} mpm_nonlocal_grid;

/* A grid of dim (2 or 3) axes with n[a] units of size h[a] each and the
 * ghost rules of its 2 dim faces (enum mpm_nonlocal_ghost; 2D reads
 * ghost[0..3]); no open outlet. g must be zeroed or set before: its stamp
 * goes on from the one it had. MPM_EINVAL for a dimension other than 2 or
 * 3, n < 1, h not > 0 or finite, an unknown rule, or a periodic face whose
 * opposite face is not periodic. */
int mpm_nonlocal_grid_set(mpm_nonlocal_grid *g, int dim, const int n[], const double h[],
                          const int ghost[], mpm_err *err);

/* The units c of face `face` with lo[b] <= c_b < hi[b] on the axes b along
 * it (lo, hi indexed by axis; the entries of the face's own axis and, in
 * 2D, of z are not read) become a free surface there, Neumann whatever the
 * face's rule (one open face at a time). */
void mpm_nonlocal_grid_open_faces(mpm_nonlocal_grid *g, int face, const int lo[3],
                                  const int hi[3]);

/* Narrow the open faces to the units e of the open range with mask[e] = 1
 * (nu entries, kept by the caller while the grid is used; NULL: the whole
 * range). */
void mpm_nonlocal_grid_open_mask(mpm_nonlocal_grid *g, const unsigned char *mask);

/* Unit index of c (0 <= c_a < n_a; c[2] = 0 in 2D). */
static inline size_t mpm_nonlocal_grid_index(const mpm_nonlocal_grid *g, const int c[3])
{
  return (size_t)c[0] + g->stride[1] * (size_t)c[1] + g->stride[2] * (size_t)c[2];
}

/* The unit across face `face` of unit c (index e), filled or not, its
 * index (periodic faces wrapped) to *nb: 1, or 0 across a face of the grid
 * that is not periodic. */
int mpm_nonlocal_grid_face_unit(const mpm_nonlocal_grid *g, const int c[3], size_t e, int face,
                                size_t *nb);

/* Across face `face` of unit c (index e): a filled neighbour (sm > 0),
 * whose index (periodic faces wrapped) goes to *nb and 0 is returned, or a
 * ghost g_ghost = k g_e, k = +1 (Neumann: empty neighbour, Neumann face,
 * open outlet) or -1 (Dirichlet), and k is returned (*nb unset). */
int mpm_nonlocal_grid_side(const mpm_nonlocal_grid *g, const double *sm, const int c[3],
                           size_t e, int face, size_t *nb);

/* lap[e] on every unit from ge (the stencil at the top; 0 on empty units).
 * Independent per unit: on all threads when the grid has more than 256 units. */
void mpm_nonlocal_grid_laplacian(const mpm_nonlocal_grid *g, const double *sm,
                                 const double *ge, double *lap);

/* Row of filled unit c (index e) of I - c L_h (coefficient coef = c >= 0;
 * the top): its diagonal is returned, its off-diagonal entries go to
 * nb[0 .. *count-1] (unit indices, in face order, a neighbour once per face
 * it is found across) and val[] (-c w_f); nb and val have room for
 * MPM_NONLOCAL_FACES. */
double mpm_nonlocal_grid_row(const mpm_nonlocal_grid *g, const double *sm, const int c[3],
                             size_t e, double coef, size_t nb[], double val[], int *count);

/* Extent rule ([DK-silo] §5.2 (i), material.g_average = "extent"): the
 * units of g that the box of half-widths h[a] (in unit sizes, 0 <= h[a] <=
 * 1/2 up to round-off) centred at local position u[a] (0 ... 1) of unit c
 * overlaps, each with the fraction of the box's volume inside the mesh
 * that lies in it (the box's part beyond a non-periodic face dropped, one
 * across a periodic face wrapped). Fills the 2^dim slots of part and w, x
 * fastest, then y, then z; unused slots get unit c and weight 0. */
void mpm_nonlocal_grid_parts(const mpm_nonlocal_grid *g, const int c[3], const double u[3],
                             const double h[3], int *part, double *w);

/* The w-weighted mean of f over the filled units (sm > 0) among the nslot
 * (unit, weight) pairs part, w; 0 when none of them is filled. */
double mpm_nonlocal_grid_parts_mean(const double *sm, const double *f, const int *part,
                                    const double *w, int nslot);

#endif
