/* mesh.h: structured 2D background mesh (MODEL.md section 3).
 *
 * nx x ny square-ish "units" of size dx x dy from (x0, y0). Topology Q4
 * (bilinear unit) or T3 (each unit split into two linear triangles along a
 * diagonal chosen per unit: "/" bottom-left to top-right, "\" the other, or
 * "mirror": "/" left of x = mirror_x and "\" right of it, [DK-silo] 7.1).
 * Periodic directions alias node i = nx with i = 0 (likewise j): aliased nodes
 * share one storage index, so every nodal array has mesh.nnodes entries.
 * The per-axis pieces (mpm_mesh_axis_*) do not depend on the dimension; the
 * 3D mesh of boxes (box.h) is built on them. */
#ifndef MPM_MESH_MESH_H
#define MPM_MESH_MESH_H

#include <stddef.h>

#include "core/config.h"
#include "core/error.h"

enum mpm_topology { MPM_TOPO_Q4 = 0, MPM_TOPO_T3 };
enum mpm_diagonal { MPM_DIAG_SLASH = 0, MPM_DIAG_BACKSLASH, MPM_DIAG_MIRROR };

typedef struct mpm_mesh {
  /* set by the caller before mpm_mesh_setup */
  int nx, ny;            /* units */
  double x0, y0, dx, dy; /* origin and unit size [m] */
  int topology;          /* enum mpm_topology */
  int diagonal;          /* enum mpm_diagonal (T3 only) */
  double mirror_x;       /* mirror line for MPM_DIAG_MIRROR [m] */
  int periodic_x, periodic_y;
  /* derived by mpm_mesh_setup */
  int snx, sny;          /* stored nodes per row / column (nx or nx+1) */
  int nnodes;            /* snx * sny */
  double lx, ly;         /* domain size nx*dx, ny*dy */
  double idx, idy;       /* 1/dx, 1/dy (kept for the hot loops) */
} mpm_mesh;

/* Validate the caller's fields and fill the derived ones. */
int mpm_mesh_setup(mpm_mesh *m, mpm_err *err);

/* Name <-> enum ("q4", "t3"; "/", "\\", "mirror"): -1 / NULL if unknown. */
int mpm_mesh_topology_from_name(const char *name);
const char *mpm_mesh_topology_name(int topology);
int mpm_mesh_diagonal_from_name(const char *name);
const char *mpm_mesh_diagonal_name(int diagonal);

/* The mesh of a resolved input (mesh section, periodic from the bc section),
 * set up; MPM_EINPUT names an unknown topology or diagonal. */
int mpm_mesh_from_config(mpm_mesh *m, const mpm_config *cfg, mpm_err *err);

/* Storage index of logical node (i, j), 0 <= i <= nx, 0 <= j <= ny, with
 * periodic aliasing. */
int mpm_mesh_node(const mpm_mesh *m, int i, int j);

/* Position of logical node (i, j). */
void mpm_mesh_node_pos(const mpm_mesh *m, int i, int j, double *x, double *y);

/* Wrap a position into the domain along periodic directions. */
void mpm_mesh_wrap(const mpm_mesh *m, double *x, double *y);

/* Unit (i, j) containing (x, y) (after wrapping); a point on the upper or right
 * boundary belongs to the last unit. Returns MPM_OK or MPM_EOUTSIDE. */
int mpm_mesh_unit(const mpm_mesh *m, double x, double y, int *i, int *j);

/* 1 if the T3 unit (i, j) is cut along "/", 0 if along "\". */
int mpm_mesh_unit_is_slash(const mpm_mesh *m, int i, int j);

/* Linear (T3) or bilinear (Q4) basis of the element containing (x, y):
 * writes the storage ids of its nodes, N and grad N; returns the node count
 * (3 or 4), or -1 when (x, y) is outside a non-periodic direction.
 * The same as mpm_mesh_locate followed by mpm_mesh_basis_at. */
int mpm_mesh_basis(const mpm_mesh *m, double x, double y,
                   int node[4], double N[4], double dNx[4], double dNy[4]);

/* ---- the same, in pieces, inline for the hot loops (stencils, the step) ---- */

/* Distance s wrapped into [0, len) along a periodic axis (len after
 * round-off of a tiny negative s is the same point: 0). */
double mpm_mesh_axis_wrap(double s, double len);

/* A coordinate x along a periodic axis of origin o and length len wrapped
 * into [o, o + len) (left alone if not finite: the health check reports it). */
void mpm_mesh_axis_wrap_coord(double *x, double o, double len);

/* Unit k in [0, n-1] and local coordinate u in [0, 1] at distance s in
 * [0, n/ih] from the start of an axis of n units of size 1/ih (a point on
 * the upper end belongs to the last unit). */
static inline void mpm_mesh_axis_unit(double s, double ih, int n, int *k, double *u)
{
  double xi = s * ih;           /* position in units */
  int kk = (int)xi;
  kk = kk > n - 1 ? n - 1 : kk;
  double f = xi - kk;
  *k = kk;
  *u = f > 1.0 ? 1.0 : f;       /* round-off at the upper end */
}

/* Unit k in [0, n-1] and local coordinate u in [0, 1] of x along one axis of
 * origin o, length len, unit size 1/ih. Periodic axes wrap first; a point on
 * the upper end belongs to the last unit. Returns 0, or -1 outside (or NaN). */
static inline int mpm_mesh_axis_locate(double x, double o, double len, double ih, int n,
                                       int periodic, int *k, double *u)
{
  double s;
  if (periodic) {
    s = x - o;
    if (!(s >= 0.0 && s < len))
      s = mpm_mesh_axis_wrap(s, len);
    if (!(s >= 0.0 && s <= len))
      return -1;                /* non-finite */
  } else {
    if (!(x >= o && x <= o + len))
      return -1;
    s = x - o;
  }
  mpm_mesh_axis_unit(s, ih, n, k, u);
  return 0;
}

/* Offset d between two units along an axis of n units (a corner's unit less
 * its point's); on a periodic axis the one of d, d - n, d + n nearest 0 (a
 * corner wrapped round). */
static inline int mpm_mesh_axis_offset(int d, int n, int periodic)
{
  if (periodic && 2 * d > n)
    return d - n;
  if (periodic && 2 * d < -n)
    return d + n;
  return d;
}

/* Storage index along an axis of n units of logical node k, for k within
 * one period of [0, n) (the general case: any k, mpm_mesh_node). */
static inline int mpm_mesh_axis_node(int k, int n, int periodic)
{
  if (!periodic)
    return k;
  return k < 0 ? k + n : k >= n ? k - n : k;
}

/* Unit (i, j) of (x, y) (after wrapping) and the local coordinates (u, v) in
 * [0, 1]^2 of the point in it; 0, or -1 outside a non-periodic direction. */
static inline int mpm_mesh_locate(const mpm_mesh *m, double x, double y, int *i, int *j,
                                  double *u, double *v)
{
  return mpm_mesh_axis_locate(x, m->x0, m->lx, m->idx, m->nx, m->periodic_x, i, u) ||
         mpm_mesh_axis_locate(y, m->y0, m->ly, m->idy, m->ny, m->periodic_y, j, v) ? -1 : 0;
}

/* 1 if the T3 units of column i are cut along "/", 0 along "\" (the rule
 * does not depend on the row). */
static inline int mpm_mesh_column_is_slash(const mpm_mesh *m, int i)
{
  switch (m->diagonal) {
  case MPM_DIAG_SLASH:
    return 1;
  case MPM_DIAG_BACKSLASH:
    return 0;
  default:  /* mirror: "/" when the unit centre is left of x = mirror_x */
    return m->x0 + (i + 0.5) * m->dx < m->mirror_x;
  }
}

/* Storage ids of the corners of unit (i, j) in the order (i, j), (i+1, j),
 * (i+1, j+1), (i, j+1), with periodic aliasing, from n0 = j snx + i, the
 * storage id of the first. */
static inline void mpm_mesh_corners_from(const mpm_mesh *m, int n0, int i, int j, int c[4])
{
  int dx = 1, dy = m->snx;                          /* the next column, the next row */
  if (m->periodic_x && i + 1 == m->nx)
    dx = 1 - m->nx;                                 /* node nx aliases node 0 */
  if (m->periodic_y && j + 1 == m->ny)
    dy = (1 - m->ny) * m->snx;
  c[0] = n0;
  c[1] = n0 + dx;
  c[2] = n0 + dx + dy;
  c[3] = n0 + dy;
}

/* The same from (i, j) alone. */
static inline void mpm_mesh_unit_corners(const mpm_mesh *m, int i, int j, int c[4])
{
  mpm_mesh_corners_from(m, j * m->snx + i, i, j, c);
}

/* Bilinear (Q4) basis at local (u, v) on the unit corners (order of
 * mpm_mesh_unit_corners), with 1/dx = ix, 1/dy = iy:
 *   N = (1-u)(1-v), u(1-v), uv, (1-u)v,  grad N = (dN/du / dx, dN/dv / dy),
 * written per corner a as N_a = f_a g_a with f = (1-u, u, u, 1-u),
 * g = (1-v, 1-v, v, v), dN_a/du = su_a g_a, dN_a/dv = sv_a f_a (su, sv the
 * signs), so the four corners are one vector operation each. */
static inline void mpm_mesh_basis_q4(double u, double v, double ix, double iy, double N[4],
                                     double dNx[4], double dNy[4])
{
  const double su[4] = {-1.0, 1.0, 1.0, -1.0}, cu[4] = {1.0, 0.0, 0.0, 1.0};
  const double sv[4] = {-1.0, -1.0, 1.0, 1.0}, cv[4] = {1.0, 1.0, 0.0, 0.0};
#pragma omp simd
  for (int a = 0; a < 4; a++) {
    const double f = cu[a] + su[a] * u, g = cv[a] + sv[a] * v;    /* 1-u or u, 1-v or v */
    N[a] = f * g;
    dNx[a] = su[a] * g * ix;
    dNy[a] = sv[a] * f * iy;
  }
}

/* Values N at local (u, v) on the four unit corners (order of
 * mpm_mesh_unit_corners) of a unit of topology `topology`, cut along "/"
 * if `slash` (T3). Returns the mask of the corners of the element (bit a
 * for corner a): all four for Q4; for T3 the three of the triangle holding
 * (u, v) (ties on the diagonal go to the lower one), the fourth getting
 * N = 0. The T3 values are selections, not branches, so that a loop over
 * points or corners vectorises. */
static inline unsigned mpm_mesh_shape_unit(int topology, int slash, double u, double v,
                                           double N[4])
{
  if (topology == MPM_TOPO_Q4) {
    N[0] = (1.0 - u) * (1.0 - v);
    N[1] = u * (1.0 - v);
    N[2] = u * v;
    N[3] = (1.0 - u) * v;
    return 0xfu;
  }
  if (slash) {
    const int lo = u >= v;       /* lower: corners 0 1 2, N = 1-u, u-v, v; upper: 0 2 3, 1-v, u, v-u */
    N[0] = lo ? 1.0 - u : 1.0 - v;
    N[1] = lo ? u - v : 0.0;
    N[2] = lo ? v : u;
    N[3] = lo ? 0.0 : v - u;
    return lo ? 0x7u : 0xdu;
  }
  const int lo = u + v <= 1.0;   /* lower: corners 0 1 3, N = 1-u-v, u, v; upper: 1 2 3, 1-v, u+v-1, 1-u */
  N[0] = lo ? 1.0 - u - v : 0.0;
  N[1] = lo ? u : 1.0 - v;
  N[2] = lo ? 0.0 : u + v - 1.0;
  N[3] = lo ? v : 1.0 - u;
  return lo ? 0xbu : 0xeu;
}

/* The same for a unit of column i of mesh m. */
static inline unsigned mpm_mesh_shape_corners(const mpm_mesh *m, int i, double u, double v,
                                              double N[4])
{
  const int slash = m->topology == MPM_TOPO_T3 && mpm_mesh_column_is_slash(m, i);
  return mpm_mesh_shape_unit(m->topology, slash, u, v, N);
}

/* Basis of unit column i at local (u, v) on the four unit corners, in the
 * order of mpm_mesh_unit_corners: N (mpm_mesh_shape_corners) and
 * grad N = (dN/du / dx, dN/dv / dy); returns the element's corner mask.
 * Q4: mpm_mesh_basis_q4. T3 slopes dN/du, dN/dv are -1, 0 or 1, so grad N
 * is -1/dx, 0 or 1/dx (likewise in y), one table row per triangle. */
static inline unsigned mpm_mesh_basis_corners(const mpm_mesh *m, int i, double u, double v,
                                              double N[4], double dNx[4], double dNy[4])
{
  const double ix = m->idx, iy = m->idy;
  if (m->topology == MPM_TOPO_Q4) {
    mpm_mesh_basis_q4(u, v, ix, iy, N, dNx, dNy);
    return 0xfu;
  }
  const unsigned mask = mpm_mesh_shape_corners(m, i, u, v, N);
  /* dN/du and dN/dv of the four corners for the triangles 0 1 2 (mask 7),
   * 0 2 3 (d), 0 1 3 (b), 1 2 3 (e) */
  static const signed char du[4][4] = {{-1, 1, 0, 0}, {0, 0, 1, -1}, {-1, 1, 0, 0}, {0, 0, 1, -1}};
  static const signed char dv[4][4] = {{0, -1, 1, 0}, {-1, 0, 0, 1}, {-1, 0, 0, 1}, {0, -1, 1, 0}};
  const int t = mask == 0x7u ? 0 : mask == 0xdu ? 1 : mask == 0xbu ? 2 : 3;
  for (int a = 0; a < 4; a++) {
    dNx[a] = du[t][a] * ix;
    dNy[a] = dv[t][a] * iy;
  }
  return mask;
}

/* The basis of a located point (unit (i, j), local (u, v)) as a node list:
 * the element's nodes in corner order, their N and grad N; returns the count
 * (4 for Q4, 3 for T3). */
static inline int mpm_mesh_basis_at(const mpm_mesh *m, int i, int j, double u, double v,
                                    int node[4], double N[4], double dNx[4], double dNy[4])
{
  int c[4];
  mpm_mesh_unit_corners(m, i, j, c);
  if (m->topology == MPM_TOPO_Q4) {
    mpm_mesh_basis_corners(m, i, u, v, N, dNx, dNy);
    for (int a = 0; a < 4; a++)
      node[a] = c[a];
    return 4;
  }
  double Nc[4], gx[4], gy[4];
  const unsigned mask = mpm_mesh_basis_corners(m, i, u, v, Nc, gx, gy);
  int k = 0;
  for (int a = 0; a < 4; a++)
    if (mask >> a & 1u) {
      node[k] = c[a];
      N[k] = Nc[a];
      dNx[k] = gx[a];
      dNy[k] = gy[a];
      k++;
    }
  return k;
}

/* ---- points in bands of unit rows (bands.c) ----------------------------------
 * For loops in which each point adds to the rows of nodes or units near it:
 * a point in unit row j writes to rows j - lo .. j + hi (nodes: lo = r,
 * hi = 1 + r for a stencil reaching r units beyond the point's own; units
 * of the point's centre: lo = hi = 0). A band is h = max(1, lo + hi)
 * consecutive unit rows (the last band takes the remainder), so two bands
 * that are not neighbours never write to the same row: the bands of one
 * colour (b mod ncolour) may run in parallel, the colours one after the
 * other, and then every written entry sums its shares band by band and in
 * point order within a band, whatever the number of threads. On a periodic
 * y axis the band count is even so that the colours alternate round it. */
typedef struct mpm_mesh_bands {
  int h, nb, ncolour;  /* rows per band, bands, colours (1: lo + hi = 0, or one band) */
  int *start;          /* [nb + 1]: band k holds idx[start[k] .. start[k + 1]) */
  int *idx;            /* [n] point indices, band by band, increasing within a band */
  size_t n, cap;       /* points binned, room in idx */
  int *band_of_row;    /* [ny] */
  int ny, lo, hi, rcap;  /* the layout's rows and reach; room in band_of_row */
  int *tcount;         /* [threads (nb + 1)] the threads' counts per band */
  size_t tcap;
} mpm_mesh_bands;

mpm_mesh_bands *mpm_mesh_bands_alloc(void);
void mpm_mesh_bands_free(mpm_mesh_bands *b);  /* accepts NULL */

/* Bin n points by their unit rows row[p] (0 <= row[p] < ny, the rows of
 * an axis, periodic or not: the y axis of a plane mesh, the z layers of a
 * box mesh) for writes to rows row - lo .. row + hi. */
int mpm_mesh_bands_sort(mpm_mesh_bands *b, int ny, int periodic, int lo, int hi, size_t n,
                        const int *row, mpm_err *err);

#endif