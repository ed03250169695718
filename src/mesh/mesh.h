/* mesh.h: the structured background mesh of 2 or 3 dimensions (MODEL.md
 * section 3).
 *
 * n[0] x n[1] (x n[2]) units of size h[0] x h[1] (x h[2]) from the origin
 * o. Every axis has the same fields, so code over the axes is written once;
 * the plane's absent z axis collapses to one unit of unit thickness (n = 1,
 * h = 1, one node layer), so a unit's volume is an area per unit thickness
 * and the 3D formulas give the plane's. The fields have their axis names
 * too (nx = n[0], dy = h[1], periodic_z = periodic[2], ...).
 *
 * Topology: in the plane, Q4 (bilinear units) or T3 (each unit split into
 * two linear triangles along a diagonal chosen per unit: "/" bottom-left to
 * top-right, "\" the other, or "mirror": "/" left of x = mirror_x and "\"
 * right of it, [DK-silo] 7.1); in 3D, boxes with the trilinear basis (Q4
 * is the multilinear basis of either dimension; T3 is plane only).
 * Periodic axes alias node i = n with i = 0: aliased nodes share one
 * storage index, id = (k_s sny + j_s) snx + i_s, so every nodal array has
 * mesh.nnodes entries. Units are numbered e = i + nx (j + ny k).
 *
 * The corners of a unit are numbered as a VTK/XDMF quadrilateral or
 * hexahedron: (i, j), (i+1, j), (i+1, j+1), (i, j+1), then in 3D the same
 * four on the top face: corner a lies at the upper end of axis 0 when
 * (a ^ a >> 1) & 1, of axis d >= 1 when bit d of a is set. */
#ifndef MPM_MESH_MESH_H
#define MPM_MESH_MESH_H

#include <math.h>
#include <stddef.h>

#include "core/config.h"
#include "core/error.h"

enum mpm_topology { MPM_TOPO_Q4 = 0, MPM_TOPO_T3 };
enum mpm_diagonal { MPM_DIAG_SLASH = 0, MPM_DIAG_BACKSLASH, MPM_DIAG_MIRROR };

/* Most corners of a unit (a box). */
#define MPM_MESH_CORNERS 8

typedef struct mpm_mesh {
  /* set by the caller before mpm_mesh_setup */
  int dim;                                                  /* 2 or 3 (0: 2) */
  union { struct { int nx, ny, nz; }; int n[3]; };          /* units (nz: 3D) */
  union { struct { double x0, y0, z0; }; double o[3]; };    /* origin [m] */
  union { struct { double dx, dy, dz; }; double h[3]; };    /* unit size [m] */
  int topology;                                             /* enum mpm_topology */
  int diagonal;                                             /* enum mpm_diagonal (T3) */
  double mirror_x;                                          /* mirror line (T3) [m] */
  union { struct { int periodic_x, periodic_y, periodic_z; }; int periodic[3]; };
  /* derived by mpm_mesh_setup (the plane's z axis: 1 unit of size 1) */
  union { struct { int snx, sny, snz; }; int sn[3]; };      /* stored nodes (n or n + 1) */
  int nnodes;                                               /* snx sny snz */
  size_t nunits;                                            /* nx ny nz */
  union { struct { double lx, ly, lz; }; double len[3]; };  /* domain size n h */
  union { struct { double idx, idy, idz; }; double ih[3]; };/* 1/h */
} mpm_mesh;

/* Validate the caller's fields and fill the derived ones; MPM_EINPUT names
 * the field (mesh.nx, mesh.dz, ...) and the allowed range. */
int mpm_mesh_setup(mpm_mesh *m, mpm_err *err);

/* Name <-> enum ("q4", "t3"; "/", "\\", "mirror"): -1 / NULL if unknown. */
int mpm_mesh_topology_from_name(const char *name);
const char *mpm_mesh_topology_name(int topology);
int mpm_mesh_diagonal_from_name(const char *name);
const char *mpm_mesh_diagonal_name(int diagonal);

/* The mesh of a resolved input (mesh section, 3D when mesh.nz > 0; periodic
 * axes from the bc section), set up; MPM_EINPUT names an unknown topology or
 * diagonal. err may be NULL. */
int mpm_mesh_from_config(mpm_mesh *m, const mpm_config *cfg, mpm_err *err);

/* Storage index of logical node (i, j, k) (k = 0 in the plane), with
 * periodic aliasing (any integer index along a periodic axis). */
int mpm_mesh_node(const mpm_mesh *m, int i, int j, int k);

/* Position of logical node (i, j, k) (z = 0 in the plane). */
void mpm_mesh_node_pos(const mpm_mesh *m, int i, int j, int k, double x[3]);

/* Index of unit c, c[0] + nx (c[1] + ny c[2]) (c[2] = 0 in the plane). */
static inline size_t mpm_mesh_unit_index(const mpm_mesh *m, const int c[3])
{
  return (size_t)c[0] + (size_t)m->nx * ((size_t)c[1] + (size_t)m->ny * (size_t)c[2]);
}

/* ---- per axis: the pieces every dimension is built of ------------------------ */

/* Distance s wrapped into [0, len) along a periodic axis (len after
 * round-off of a tiny negative s is the same point: 0). */
double mpm_mesh_axis_wrap(double s, double len);

/* A coordinate x along a periodic axis of origin o and length len wrapped
 * into [o, o + len) (left alone if not finite: the health check reports it). */
void mpm_mesh_axis_wrap_coord(double *x, double o, double len);

/* Unit k in [0, n-1] and local coordinate u in [0, 1] at distance s in
 * [0, n/ih] from the start of an axis of n units of size 1/ih (a point on
 * the upper end belongs to the last unit), with last = n - 1 and k as
 * doubles (integers), for a loop whose tests must all be of doubles to
 * vectorise. */
static inline void mpm_mesh_axis_unit_real(double s, double ih, double last, double *k, double *u)
{
  const double xi = s * ih;     /* position in units */
  double kk = trunc(xi);
  kk = kk > last ? last : kk;
  const double f = xi - kk;
  *k = kk;
  *u = f > 1.0 ? 1.0 : f;       /* round-off at the upper end */
}

/* The same with n units and k an int (its operations on ints: the plane's
 * vectorised loops run faster so, and give the same values). */
static inline void mpm_mesh_axis_unit(double s, double ih, int n, int *k, double *u)
{
  const double xi = s * ih;     /* position in units */
  int kk = (int)xi;
  kk = kk > n - 1 ? n - 1 : kk;
  const double f = xi - kk;
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

/* Axis a of mesh m: mpm_mesh_axis_locate with its fields. */
static inline int mpm_mesh_locate_axis(const mpm_mesh *m, int a, double x, int *k, double *u)
{
  return mpm_mesh_axis_locate(x, m->o[a], m->len[a], m->ih[a], m->n[a], m->periodic[a], k, u);
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

/* ---- points ------------------------------------------------------------------ */

/* Unit c and local coordinates l in [0, 1] of x along the mesh's axes
 * (after wrapping periodic ones; c[2] = 0, l[2] = 0 in the plane); 0, or -1
 * outside a non-periodic face (or not finite). */
static inline int mpm_mesh_locate(const mpm_mesh *m, const double x[3], int c[3], double l[3])
{
  c[2] = 0;
  l[2] = 0.0;
  for (int a = 0; a < m->dim; a++)
    if (mpm_mesh_locate_axis(m, a, x[a], &c[a], &l[a]))
      return -1;
  return 0;
}

/* Unit c of x (after wrapping). Returns MPM_OK or MPM_EOUTSIDE. */
int mpm_mesh_unit(const mpm_mesh *m, const double x[3], int c[3]);

/* Wrap x into the domain along periodic axes. */
void mpm_mesh_wrap(const mpm_mesh *m, double x[3]);

/* ---- the element basis -------------------------------------------------------- */

/* The multilinear basis of D = 2 or 3 axes (Q4, the trilinear box) at local
 * l on the unit corners (order above), with 1/h = ih: per corner a the
 * factor along axis d is f_d = 1 - l_d or l_d (s_d = -1 or +1),
 *   N_a = f_0 f_1 (f_2),  dN_a/dx_d = s_d prod_{e != d} f_e ih_d,
 * the products taken in axis order; one vector operation per corner. */
static inline void mpm_mesh_basis_multilinear(int D, const double l[3], const double ih[3],
                                              double *N, double *const dN[3])
{
  const int nc = 1 << D;
  for (int a = 0; a < nc; a++) {
    double f[3], s[3];
    for (int d = 0; d < D; d++) {
      const int up = d == 0 ? (a ^ a >> 1) & 1 : a >> d & 1;
      s[d] = up ? 1.0 : -1.0;
      f[d] = (up ? 0.0 : 1.0) + s[d] * l[d];               /* 1 - l or l */
    }
    double n = f[0];
    for (int d = 1; d < D; d++)
      n *= f[d];
    N[a] = n;
    for (int d = 0; d < D; d++) {
      double g = s[d];
      for (int e = 0; e < D; e++)
        if (e != d)
          g *= f[e];
      dN[d][a] = g * ih[d];
    }
  }
}

/* Bilinear (Q4) basis at local (u, v) on the unit corners, with 1/dx = ix,
 * 1/dy = iy: the multilinear basis of D = 2 written out for the plane's hot
 * loops, N = (1-u)(1-v), u(1-v), uv, (1-u)v, grad N = (dN/du / dx,
 * dN/dv / dy), the same floating-point operations. */
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

/* Storage ids of the corners of plane unit (i, j) in corner order, with
 * periodic aliasing, from n0 = j snx + i, the storage id of the first. */
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

/* Storage ids of the 2^dim corners of unit c (0 <= c[a] < n[a]) in corner
 * order, with periodic aliasing. */
static inline void mpm_mesh_unit_corners(const mpm_mesh *m, const int c[3], int node[8])
{
  const int n0 = (c[2] * m->sny + c[1]) * m->snx + c[0];
  mpm_mesh_corners_from(m, n0, c[0], c[1], node);
  if (m->dim == 3) {
    const int dz = m->periodic_z && c[2] + 1 == m->nz ? (1 - m->nz) * m->snx * m->sny
                                                     : m->snx * m->sny;
    for (int a = 0; a < 4; a++)
      node[4 + a] = node[a] + dz;
  }
}

/* Values N at local (u, v) on the four corners of a plane unit of topology
 * `topology`, cut along "/" if `slash` (T3). Returns the mask of the corners
 * of the element (bit a for corner a): all four for Q4; for T3 the three of
 * the triangle holding (u, v) (ties on the diagonal go to the lower one),
 * the fourth getting N = 0. The T3 values are selections, not branches, so
 * that a loop over points or corners vectorises. */
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

/* The values N of the element basis at local l on the corners of unit c of
 * mesh m (Q4 or T3 in the plane, the box in 3D). Returns the mask of the
 * corners of the element (all 2^dim but on T3, mpm_mesh_shape_unit). */
static inline unsigned mpm_mesh_shape_corners(const mpm_mesh *m, const int c[3],
                                              const double l[3], double N[8])
{
  if (m->dim == 3) {
    const double f[4] = {1.0 - l[0], l[0], l[0], 1.0 - l[0]};
    const double g[4] = {1.0 - l[1], 1.0 - l[1], l[1], l[1]};
    for (int a = 0; a < 4; a++) {
      N[a] = f[a] * g[a] * (1.0 - l[2]);
      N[4 + a] = f[a] * g[a] * l[2];
    }
    return 0xffu;
  }
  const int slash = m->topology == MPM_TOPO_T3 && mpm_mesh_column_is_slash(m, c[0]);
  return mpm_mesh_shape_unit(m->topology, slash, l[0], l[1], N);
}

/* Basis of plane unit column i at local (u, v) on the four unit corners:
 * N (mpm_mesh_shape_unit) and grad N = (dN/du / dx, dN/dv / dy); returns the
 * element's corner mask. Q4: mpm_mesh_basis_q4. T3 slopes dN/du, dN/dv are
 * -1, 0 or 1, so grad N is -1/dx, 0 or 1/dx (likewise in y), one table row
 * per triangle. */
static inline unsigned mpm_mesh_basis_corners(const mpm_mesh *m, int i, double u, double v,
                                              double N[4], double dNx[4], double dNy[4])
{
  const double ix = m->idx, iy = m->idy;
  if (m->topology == MPM_TOPO_Q4) {
    mpm_mesh_basis_q4(u, v, ix, iy, N, dNx, dNy);
    return 0xfu;
  }
  const int slash = mpm_mesh_column_is_slash(m, i);
  const unsigned mask = mpm_mesh_shape_unit(m->topology, slash, u, v, N);
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

/* The element basis of a located point (unit c, local l) as a node list:
 * the element's nodes in corner order, their N and grad N (dN[d][k] =
 * dN_k/dx_d); returns the count (4 for Q4, 3 for T3, 8 for a box). */
static inline int mpm_mesh_basis_at(const mpm_mesh *m, const int c[3], const double l[3],
                                    int *node, double *N, double *const dN[3])
{
  int id[8];
  mpm_mesh_unit_corners(m, c, id);
  if (m->dim == 3) {
    mpm_mesh_basis_multilinear(3, l, m->ih, N, dN);
    for (int a = 0; a < 8; a++)
      node[a] = id[a];
    return 8;
  }
  double Nc[4], gx[4], gy[4];
  const unsigned mask = mpm_mesh_basis_corners(m, c[0], l[0], l[1], Nc, gx, gy);
  int k = 0;
  for (int a = 0; a < 4; a++)
    if (mask >> a & 1u) {
      node[k] = id[a];
      N[k] = Nc[a];
      dN[0][k] = gx[a];
      dN[1][k] = gy[a];
      k++;
    }
  return k;
}

/* The element basis at x: mpm_mesh_locate then mpm_mesh_basis_at; returns
 * the count, or -1 when x is outside a non-periodic face. */
int mpm_mesh_basis(const mpm_mesh *m, const double x[3], int *node, double *N,
                   double *const dN[3]);

/* ---- points in bands of unit rows (bands.c) ----------------------------------
 * For loops in which each point adds to the rows of nodes or units near it:
 * a point in unit row j (the units along the mesh's last axis: y in the
 * plane, z in 3D) writes to rows j - lo .. j + hi (nodes: lo = r, hi = 1 + r
 * for a stencil reaching r units beyond the point's own; units of the
 * point's centre: lo = hi = 0). A band is h = max(1, lo + hi) consecutive
 * unit rows (the last band takes the remainder), so two bands that are not
 * neighbours never write to the same row: the bands of one colour (b mod
 * ncolour) may run in parallel, the colours one after the other, and then
 * every written entry sums its shares band by band and in point order
 * within a band, whatever the number of threads. On a periodic axis the
 * band count is even so that the colours alternate round it. */
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
 * an axis, periodic or not) for writes to rows row - lo .. row + hi. */
int mpm_mesh_bands_sort(mpm_mesh_bands *b, int ny, int periodic, int lo, int hi, size_t n,
                        const int *row, mpm_err *err);

#endif
