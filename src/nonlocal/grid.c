/* grid.c: the unit grid of the element fluidity in 2 or 3 dimensions
 * (grid.h): the side rule across each face, the (2D+1)-point Laplacian
 *   lap_e = sum_a (g_{a+} - 2 g_e + g_{a-}) / h_a^2
 * and the row of I - c L_h for the backward-Euler solve (implicit.h).
 * Ghosts: Neumann g_ghost = g_e (empty neighbour, Neumann face, open
 * outlet), Dirichlet g_ghost = -g_e (g = 0 on the face, midway between the
 * centres), periodic wrap ([DK-silo] §4, §6, §7.1).
 *
 * The Laplacian is one kernel for both dimensions, instantiated with D a
 * constant (2 or 3) so that the face loop unrolls: in 2D it does the
 * floating-point operations of the 5-point stencil in the order it always
 * did, (g_E - 2 g_e + g_W)/dx^2 + (g_N - 2 g_e + g_S)/dy^2. */
#include "nonlocal/grid.h"

#include <math.h>

static const char *const face_names[MPM_NONLOCAL_FACES] = {"-x", "+x", "-y", "+y", "-z",
                                                           "+z"};

int mpm_nonlocal_grid_set(mpm_nonlocal_grid *g, int dim, const int n[], const double h[],
                          const int ghost[], mpm_err *err)
{
  if (dim != 2 && dim != 3)
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: a unit grid of %d dimensions (2 or 3)", dim);
  mpm_nonlocal_grid t = {.dim = dim, .open_face = -1};
  size_t nu = 1;
  for (int a = 0; a < 3; a++) {
    const int na = a < dim ? n[a] : 1;
    if (na < 1)
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: %d units along axis %d", na, a);
    if (a < dim && !(h[a] > 0.0 && isfinite(h[a])))
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: unit size %g m along axis %d", h[a], a);
    t.n[a] = na;
    t.stride[a] = nu;
    nu *= (size_t)na;
    t.ih2[a] = a < dim ? 1.0 / (h[a] * h[a]) : 0.0;   /* 1/h^2 */
  }
  t.nu = nu;
  for (int f = 0; f < 2 * dim; f++) {
    if (ghost[f] != MPM_GHOST_NEUMANN && ghost[f] != MPM_GHOST_DIRICHLET &&
        ghost[f] != MPM_GHOST_PERIODIC)
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: face %s has unknown ghost rule %d",
                         face_names[f], ghost[f]);
    t.ghost[f] = ghost[f];
  }
  for (int a = 0; a < dim; a++)
    if ((t.ghost[2 * a] == MPM_GHOST_PERIODIC) != (t.ghost[2 * a + 1] == MPM_GHOST_PERIODIC))
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: faces %s and %s must both be periodic or "
                         "neither", face_names[2 * a], face_names[2 * a + 1]);
  t.stamp = g->stamp + 1;
  *g = t;
  return MPM_OK;
}

void mpm_nonlocal_grid_open_faces(mpm_nonlocal_grid *g, int face, const int lo[3],
                                  const int hi[3])
{
  g->open_face = face;
  for (int b = 0; b < 3; b++) {
    const int along = b != face / 2 && b < g->dim;
    g->open_lo[b] = along ? lo[b] : 0;
    g->open_hi[b] = along ? hi[b] : g->n[b];
  }
  g->stamp++;
}

void mpm_nonlocal_grid_open_mask(mpm_nonlocal_grid *g, const unsigned char *mask)
{
  g->open_mask = mask;
  g->stamp++;
}

/* 1 if unit c (index e) lies in the open range of its face on axis a (the
 * axes along the face; the range of axis a itself covers the grid) and, with
 * a mask, is marked in it. */
static inline int in_open(const mpm_nonlocal_grid *g, const int c[3], size_t e, int dim)
{
  for (int b = 0; b < dim; b++)
    if (c[b] < g->open_lo[b] || c[b] >= g->open_hi[b])
      return 0;
  return !g->open_mask || g->open_mask[e];
}

/* The index of the unit of unit c (index e) moved to cc along axis a. */
static inline size_t unit_at(const mpm_nonlocal_grid *g, const int c[3], size_t e, int a, int cc)
{
  return cc > c[a] ? e + (size_t)(cc - c[a]) * g->stride[a]
                   : e - (size_t)(c[a] - cc) * g->stride[a];
}

int mpm_nonlocal_grid_face_unit(const mpm_nonlocal_grid *g, const int c[3], size_t e, int face,
                                size_t *nb)
{
  const int a = face >> 1;
  int cc = c[a] + ((face & 1) ? 1 : -1);
  if (cc < 0 || cc >= g->n[a]) {
    if (g->ghost[face] != MPM_GHOST_PERIODIC)
      return 0;
    cc = cc < 0 ? g->n[a] - 1 : 0;                     /* periodic wrap */
  }
  *nb = unit_at(g, c, e, a, cc);
  return 1;
}

/* The side rule (grid.h, mpm_nonlocal_grid_side) for dim axes. */
static inline int side(const mpm_nonlocal_grid *g, int dim, const double *sm, const int c[3],
                       size_t e, int face, size_t *nb)
{
  const int a = face >> 1;
  int cc = c[a] + ((face & 1) ? 1 : -1);
  if (cc < 0 || cc >= g->n[a]) {
    if (face == g->open_face && in_open(g, c, e, dim))
      return 1;                                        /* open outlet: free surface */
    if (g->ghost[face] == MPM_GHOST_DIRICHLET)
      return -1;                                       /* g_ghost = -g_e: g = 0 on the face */
    if (g->ghost[face] == MPM_GHOST_NEUMANN)
      return 1;                                        /* g_ghost = g_e: d_n g = 0 */
    cc = cc < 0 ? g->n[a] - 1 : 0;                     /* periodic wrap */
  }
  const size_t f = unit_at(g, c, e, a, cc);
  if (!(sm[f] > 0.0))
    return 1;                                          /* empty neighbour: Neumann */
  *nb = f;
  return 0;
}

int mpm_nonlocal_grid_side(const mpm_nonlocal_grid *g, const double *sm, const int c[3],
                           size_t e, int face, size_t *nb)
{
  return side(g, g->dim, sm, c, e, face, nb);
}

/* g across a face of unit c: the filled neighbour's g, else the ghost k g_e
 * (exact: a product with +-1). */
static inline double across(const mpm_nonlocal_grid *g, int dim, const double *sm,
                            const double *ge, const int c[3], size_t e, int face, double v)
{
  size_t nb = 0;
  const int k = side(g, dim, sm, c, e, face, &nb);
  return k == 0 ? ge[nb] : k * v;
}

/* lap of one row of units (c_1, c_2 fixed, c_0 = 0 .. n_0-1, from index e0). */
static inline void lap_row(const mpm_nonlocal_grid *g, int dim, const double *sm,
                           const double *ge, double *lap, int c1, int c2, size_t e0)
{
  int c[3] = {0, c1, c2};
  for (size_t e = e0; c[0] < g->n[0]; c[0]++, e++) {
    if (!(sm[e] > 0.0)) {
      lap[e] = 0.0;
      continue;
    }
    const double v = ge[e];
    double s = 0.0;
    for (int a = 0; a < dim; a++) {
      const double gm = across(g, dim, sm, ge, c, e, 2 * a, v);
      const double gp = across(g, dim, sm, ge, c, e, 2 * a + 1, v);
      const double t = (gp - 2.0 * v + gm) * g->ih2[a];        /* d2g/dx_a^2 */
      s = a == 0 ? t : s + t;
    }
    lap[e] = s;
  }
}

void mpm_nonlocal_grid_laplacian(const mpm_nonlocal_grid *g, const double *sm,
                                 const double *ge, double *lap)
{
  const int n1 = g->n[1], three = g->dim == 3;
  const long rows = (long)n1 * g->n[2];
#pragma omp parallel for schedule(static) if ((long)g->nu > 256)  /* tiny grids: no fork */
  for (long r = 0; r < rows; r++) {
    const int c1 = (int)(r % n1), c2 = (int)(r / n1);
    const size_t e0 = (size_t)r * (size_t)g->n[0];
    if (three)
      lap_row(g, 3, sm, ge, lap, c1, c2, e0);
    else
      lap_row(g, 2, sm, ge, lap, c1, c2, e0);
  }
}

double mpm_nonlocal_grid_row(const mpm_nonlocal_grid *g, const double *sm, const int c[3],
                             size_t e, double coef, size_t nb[], double val[], int *count)
{
  double diag = 1.0;
  int m = 0;
  for (int f = 0; f < 2 * g->dim; f++) {
    const double cw = coef * g->ih2[f >> 1];          /* c w_f */
    size_t q = 0;
    const int k = side(g, g->dim, sm, c, e, f, &q);
    if (k != 0) {
      diag += (1 - k) * cw;                            /* ghost k g_e: 0 or 2 c w_f */
      continue;
    }
    if (q == e)
      continue;                                        /* own neighbour: g_f - g_e = 0 */
    diag += cw;
    nb[m] = q;
    val[m++] = -cw;
  }
  *count = m;
  return diag;
}

/* The units of one axis that the extent [u - h, u + h] overlaps, in units of
 * the unit size, u the centre's position within its unit c (0 <= u <= 1) and
 * 0 <= h <= 1/2 (up to round-off): one (c, length 1) when the extent lies in c,
 * else c and the neighbour it reaches into, each with the length of its
 * part; a neighbour beyond a non-periodic face is dropped, across a periodic
 * one wrapped. Returns the number of parts (1 or 2). */
static int axis_parts(double u, double h, int c, int n, int periodic, int idx[2], double len[2])
{
  const double lo = u - h, hi = u + h;
  idx[0] = c;
  len[0] = 1.0;
  if (lo >= 0.0 && hi <= 1.0)
    return 1;                                          /* inside unit c */
  int nb = lo < 0.0 ? c - 1 : c + 1;                   /* the neighbour reached */
  len[0] = lo < 0.0 ? fmin(hi, 1.0) : 1.0 - lo;        /* part in c */
  if (nb < 0 || nb >= n) {
    if (!periodic)
      return 1;                                        /* outside the mesh: dropped */
    nb = (nb + n) % n;
  }
  idx[1] = nb;
  len[1] = lo < 0.0 ? -lo : hi - 1.0;                  /* part in the neighbour */
  return 2;
}

void mpm_nonlocal_grid_parts(const mpm_nonlocal_grid *g, const int c[3], const double u[3],
                             const double h[3], int *part, double *w)
{
  int idx[3][2] = {{c[0], c[0]}, {c[1], c[1]}, {c[2], c[2]}};
  double len[3][2] = {{1.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}};
  int np[3] = {1, 1, 1};
  for (int a = 0; a < g->dim; a++)
    np[a] = axis_parts(u[a], h[a], c[a], g->n[a], g->ghost[2 * a] == MPM_GHOST_PERIODIC,
                       idx[a], len[a]);
  double vol = 0.0;
  int k = 0;
  for (int cz = 0; cz < np[2]; cz++)
    for (int b = 0; b < np[1]; b++)
      for (int a = 0; a < np[0]; a++, k++) {
        const int at[3] = {idx[0][a], idx[1][b], idx[2][cz]};
        part[k] = (int)mpm_nonlocal_grid_index(g, at);
        w[k] = len[0][a] * len[1][b] * len[2][cz];     /* overlap (in 2D times 1, exactly) */
        vol += w[k];
      }
  for (int q = 0; q < k; q++)
    w[q] /= vol;                                       /* renormalised inside the mesh */
  const int nslot = 1 << g->dim;
  for (; k < nslot; k++) {
    part[k] = (int)mpm_nonlocal_grid_index(g, c);
    w[k] = 0.0;
  }
}

double mpm_nonlocal_grid_parts_mean(const double *sm, const double *f, const int *part,
                                    const double *w, int nslot)
{
  double sw = 0.0, swf = 0.0;
  for (int k = 0; k < nslot; k++)
    if (w[k] > 0.0 && sm[part[k]] > 0.0) {             /* filled units only */
      sw += w[k];
      swf += w[k] * f[part[k]];
    }
  return sw > 0.0 ? swf / sw : 0.0;
}
