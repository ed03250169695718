/* fluidity.c: element-averaged granular fluidity and its Laplacian with
 * ghost rules on the units of a mesh of either dimension (MODEL.md section
 * 5 steps 1-2; [DK-silo] §5.2 (i)-(ii), eq. 5.1; boundary conditions on g
 * from [DK-silo] §4 and §6).
 *
 *   g_e   = sum_{p dense} w_pe m_p g_p / sum_{p dense} w_pe m_p
 * w_pe = 1 for the unit containing the centre of p (centre rule) or the
 * fraction of the extent of p lying in unit e (extent rule, [DK-silo]
 * §5.2 (i); the extent is the axis-aligned box of half-widths
 * sum_k |r_ka|, parts outside the mesh dropped, periodic faces wrapped).
 *   lap_e = sum_a (g_{a+} - 2 g_e + g_{a-}) / h_a^2
 * Ghosts: Neumann g_ghost = g_e (empty neighbour, free face, frictionless or
 * symmetry wall), Dirichlet g_ghost = -g_e (no-slip wall: g = 0 on the face,
 * midway between the centres), periodic wrap. The stencil and the side rule
 * are those of the unit grid (grid.c); here the faces of the mesh set its
 * rules. */
#include "nonlocal/nonlocal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/names.h"
#include "nonlocal/field.h"

static const char *const rule_names[] = {"centre", "extent"};
static const char *const wall_names[] = {"dirichlet", "neumann"};

int mpm_nonlocal_wall_from_name(const char *name)
{
  return mpm_names_index(wall_names, MPM_NAMES_COUNT(wall_names), name);
}

const char *mpm_nonlocal_wall_name(int wall)
{
  return mpm_names_at(wall_names, MPM_NAMES_COUNT(wall_names), wall);
}

int mpm_nonlocal_rule_from_name(const char *name)
{
  return mpm_names_index(rule_names, MPM_NAMES_COUNT(rule_names), name);
}

const char *mpm_nonlocal_rule_name(int rule)
{
  return mpm_names_at(rule_names, MPM_NAMES_COUNT(rule_names), rule);
}

int mpm_nonlocal_open_faces(mpm_nonlocal *ws, int face, const int lo[3], const int hi[3],
                            const unsigned char *open, mpm_err *err)
{
  mpm_nonlocal_grid_open_faces(&ws->grid, face, lo, hi);
  if (!open)
    return MPM_OK;
  if (!ws->open_mask && !(ws->open_mask = malloc(ws->grid.nu)))
    return mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the outlet's unit faces");
  memcpy(ws->open_mask, open, ws->grid.nu);
  mpm_nonlocal_grid_open_mask(&ws->grid, ws->open_mask);
  return MPM_OK;
}

void mpm_nonlocal_walls_neumann(mpm_nonlocal *ws)
{
  for (int k = 0; k < 2 * ws->grid.dim; k++)
    if (ws->grid.ghost[k] == MPM_GHOST_DIRICHLET)
      ws->grid.ghost[k] = MPM_GHOST_NEUMANN;
  ws->grid.stamp++;
}

/* 1 if unit c lies in the open range of the outlet on face f (and, with a
 * mask, is marked in it). */
static int unit_open(const mpm_nonlocal_grid *g, int f, const int c[3])
{
  if (f != g->open_face)
    return 0;
  for (int b = 0; b < g->dim; b++)
    if (c[b] < g->open_lo[b] || c[b] >= g->open_hi[b])
      return 0;
  return !g->open_mask || g->open_mask[mpm_nonlocal_grid_index(g, c)];
}

void mpm_nonlocal_held_nodes(const mpm_nonlocal *ws, const mpm_mesh *m, unsigned char *held)
{
  for (int i = 0; i < m->nnodes; i++)
    held[i] = 0;
  const mpm_nonlocal_grid *g = &ws->grid;
  const int kz = m->dim == 3 ? m->nz : 0;
  for (int f = 0; f < 2 * m->dim; f++) {
    if (g->ghost[f] != MPM_GHOST_DIRICHLET)
      continue;
    const int a = f / 2, at = f % 2 ? m->n[a] : 0;
    int c[3];
    for (c[2] = 0; c[2] <= kz; c[2]++)
      for (c[1] = 0; c[1] <= m->ny; c[1]++)
        for (c[0] = 0; c[0] <= m->nx; c[0]++) {
          if (c[a] != at)
            continue;
          /* a node of an open unit face is free: the unit faces around it
           * along the face, one of them open */
          int u[3] = {0, 0, 0}, open = 0;
          for (int k = 0; k < 1 << m->dim && !open; k++) {
            int ok = 1;
            for (int b = 0; b < m->dim; b++) {
              u[b] = b == a ? (f % 2 ? m->n[a] - 1 : 0) : c[b] - (k >> b & 1);
              ok &= u[b] >= 0 && u[b] < m->n[b];
            }
            open = ok && unit_open(g, f, u);
          }
          if (!open)
            held[mpm_mesh_node(m, c[0], c[1], c[2])] = 1;
        }
  }
}

int mpm_nonlocal_ghost_of_bc(int bc_kind)
{
  switch (bc_kind) {
  case MPM_BC_FREE:
  case MPM_BC_FRICTIONLESS:
  case MPM_BC_SYMMETRY:
    return MPM_GHOST_NEUMANN;
  case MPM_BC_NOSLIP:
    return MPM_GHOST_DIRICHLET;
  case MPM_BC_PERIODIC:
    return MPM_GHOST_PERIODIC;
  default:
    return -1;
  }
}

void mpm_nonlocal_free(mpm_nonlocal *ws)
{
  if (!ws)
    return;
  free(ws->sm);
  free(ws->smg);
  free(ws->ge);
  free(ws->lap);
  free(ws->pe);
  free(ws->isp);
  free(ws->open_mask);
  free(ws->unit);
  free(ws->row);
  mpm_mesh_bands_free(ws->bands);
  free(ws->part);
  free(ws->w);
  free(ws->dense);
  free(ws->pn);
  if (ws->diffusion && ws->diffusion->free)
    ws->diffusion->free(ws->diffusion_state);
  free(ws);
}

int mpm_nonlocal_reserve(mpm_nonlocal *ws, size_t cap, mpm_err *err)
{
  if (cap <= ws->pcap)
    return MPM_OK;
  const int ext = ws->rule == MPM_NONLOCAL_EXTENT;
  const size_t nk = ext ? (size_t)ws->nparts * cap : 0;
  int *u = malloc(cap * sizeof *u);
  int *row = malloc(cap * sizeof *row);
  int *part = ext ? malloc(nk * sizeof *part) : NULL;
  double *w = ext ? malloc(nk * sizeof *w) : NULL;
  unsigned char *d = calloc(cap, 1);
  double *pn = calloc(cap, sizeof *pn);
  if (!u || !row || !d || !pn || (ext && (!part || !w))) {
    free(u);
    free(row);
    free(part);
    free(w);
    free(d);
    free(pn);
    return mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for %zu points", cap);
  }
  free(ws->unit);
  free(ws->row);
  free(ws->part);
  free(ws->w);
  free(ws->dense);
  free(ws->pn);
  ws->unit = u;
  ws->row = row;
  ws->part = part;
  ws->w = w;
  ws->dense = d;
  ws->pn = pn;
  ws->pcap = cap;
  return MPM_OK;
}

/* The unit grid of mesh m with the ghost rules of its faces; periodic
 * pairs must match the mesh. */
static int set_grid(mpm_nonlocal *ws, const mpm_mesh *m, const int face[], mpm_err *err)
{
  static const char *const names[2][6] = {{"left edge", "right edge", "bottom edge",
                                            "top edge", "", ""},
                                           {"face -x", "face +x", "face -y", "face +y",
                                            "face -z", "face +z"}};
  int ghost[6];
  for (int k = 0; k < 2 * m->dim; k++) {
    ghost[k] = mpm_nonlocal_ghost_of_bc(face[k]);
    if (ghost[k] < 0)
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: %s has unknown kind %d",
                         names[m->dim == 3][k], face[k]);
  }
  for (int a = 0; a < m->dim; a++)
    if ((ghost[2 * a] == MPM_GHOST_PERIODIC) != (m->periodic[a] != 0) ||
        (ghost[2 * a + 1] == MPM_GHOST_PERIODIC) != (m->periodic[a] != 0))
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: periodic %c faces must match each other "
                         "and the mesh", "xyz"[a]);
  return mpm_nonlocal_grid_set(&ws->grid, m->dim, m->n, m->h, ghost, err);
}

int mpm_nonlocal_alloc(mpm_nonlocal **out, const mpm_mesh *m, const int face[], int rule,
                       size_t cap, mpm_err *err)
{
  *out = NULL;
  if (!mpm_nonlocal_rule_name(rule))
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: unknown averaging rule %d", rule);
  if (!(m->dim == 2 || m->dim == 3) || m->nunits < 1)
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: mesh not set up (%d x %d units)",
                       m->nx, m->ny);
  mpm_nonlocal *ws = calloc(1, sizeof *ws);
  if (!ws)
    return mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the workspace");
  int rc = set_grid(ws, m, face, err);
  if (rc != MPM_OK) {
    mpm_nonlocal_free(ws);
    return rc;
  }
  const size_t nu = ws->grid.nu;
  ws->rule = rule;
  ws->nparts = 1 << m->dim;
  ws->bands = mpm_mesh_bands_alloc();
  ws->sm = calloc(nu, sizeof *ws->sm);
  ws->smg = calloc(nu, sizeof *ws->smg);
  ws->ge = calloc(nu, sizeof *ws->ge);
  ws->lap = calloc(nu, sizeof *ws->lap);
  ws->pe = calloc(nu, sizeof *ws->pe);
  ws->isp = calloc(nu, sizeof *ws->isp);
  if (!ws->bands || !ws->sm || !ws->smg || !ws->ge || !ws->lap || !ws->pe || !ws->isp) {
    mpm_nonlocal_free(ws);
    return mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for %zu units", nu);
  }
  rc = mpm_nonlocal_reserve(ws, cap > 0 ? cap : 1, err);
  if (rc != MPM_OK) {
    mpm_nonlocal_free(ws);
    return rc;
  }
  *out = ws;
  return MPM_OK;
}

/* Unit, row and (extent rule) parts of point p; 0, or 1 when it is outside
 * the mesh, 2 when its extent is wider than a unit. */
static int locate_one(mpm_nonlocal *ws, const mpm_mesh *m, const mpm_points *P, size_t p)
{
  const int D = m->dim;
  const double x[3] = {P->x[p], P->y[p], D == 3 ? P->z[p] : 0.0};
  int c[3];
  double l[3];
  if (mpm_mesh_locate(m, x, c, l))
    return 1;
  ws->unit[p] = (int)mpm_nonlocal_grid_index(&ws->grid, c);
  ws->row[p] = c[D - 1];
  if (ws->rule != MPM_NONLOCAL_EXTENT)
    return 0;
  double hw[3] = {0.0, 0.0, 0.0};                /* |r1| + |r2| (+ |r3|) along each axis, */
  for (int a = 0; a < D; a++) {                  /* in units */
    double half = fabs(P->ext[0][a][p]);
    for (int k = 1; k < D; k++)
      half += fabs(P->ext[k][a][p]);
    hw[a] = half * m->ih[a];
    if (!(hw[a] <= 0.5 + 1e-12))
      return 2;
  }
  if (D == 2)
    l[2] = 0.5;
  mpm_nonlocal_grid_parts(&ws->grid, c, l, hw, ws->part + (size_t)ws->nparts * p,
                          ws->w + (size_t)ws->nparts * p);
  return 0;
}

int mpm_nonlocal_locate(mpm_nonlocal *ws, const mpm_mesh *m, const mpm_points *pts,
                        mpm_err *err)
{
  const size_t n = pts->n;
  const int ext = ws->rule == MPM_NONLOCAL_EXTENT;
  int rc = mpm_nonlocal_reserve(ws, n, err);
  if (rc != MPM_OK)
    return rc;
  long bad = (long)n;
#pragma omp parallel for schedule(static) reduction(min : bad) if (n >= 256)
  for (size_t p = 0; p < n; p++)
    if (locate_one(ws, m, pts, p) && (long)p < bad)
      bad = (long)p;
  if (bad < (long)n) {
    const size_t p = (size_t)bad;
    char z[40] = "";
    if (m->dim == 3)
      snprintf(z, sizeof z, ", %.6g", pts->z[p]);
    if (locate_one(ws, m, pts, p) == 1)
      return mpm_err_set(err, MPM_EOUTSIDE, "nonlocal: point %d at (%.6g, %.6g%s) m is outside "
                         "the mesh", pts->id[p], pts->x[p], pts->y[p], z);
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: point %d at (%.6g, %.6g%s) m: its extent is "
                       "wider than a unit (material.g_average = \"extent\")", pts->id[p],
                       pts->x[p], pts->y[p], z);
  }
  /* the rows a point's shares reach: its own, and one either side with extents */
  const int a = m->dim - 1;
  return mpm_mesh_bands_sort(ws->bands, m->n[a], m->periodic[a], ext, ext, n, ws->row, err);
}

/* sum_e w_pe v to the units of point p (extent rule). */
static void add_parts(const mpm_nonlocal *ws, double *acc, size_t p, double v)
{
  const int *part = ws->part + (size_t)ws->nparts * p;
  const double *w = ws->w + (size_t)ws->nparts * p;
  for (int k = 0; k < ws->nparts; k++)
    if (w[k] > 0.0)
      acc[part[k]] += w[k] * v;
}

double mpm_nonlocal_point_mean(const mpm_nonlocal *ws, const double *f, size_t p)
{
  return mpm_nonlocal_grid_parts_mean(ws->sm, f, ws->part + (size_t)ws->nparts * p,
                                      ws->w + (size_t)ws->nparts * p, ws->nparts);
}

/* acc[e] += w_pe m_p f_p (and, when sm is not NULL, sm[e] += w_pe m_p) over
 * the dense points, after zeroing both: band by band, each colour's bands on
 * all threads, in point order within a band (thread-count free); in point
 * order when the bands are not those of these n points. */
static void unit_sums(mpm_nonlocal *ws, size_t n, const double *mass, const double *f,
                      const unsigned char *dense, double *sm, double *acc)
{
  const size_t nu = ws->grid.nu;
  const int ext = ws->rule == MPM_NONLOCAL_EXTENT;
  const mpm_mesh_bands *b = ws->bands;
  const int banded = b && b->n == n;
  const int nb = banded ? b->nb : 1, ncol = banded ? b->ncolour : 1;
#pragma omp parallel if (banded && n >= 256)   /* a few points: no fork */
  {
#pragma omp for schedule(static)
    for (size_t e = 0; e < nu; e++) {
      acc[e] = 0.0;
      if (sm)
        sm[e] = 0.0;
    }
    for (int col = 0; col < ncol; col++) {
#pragma omp for schedule(dynamic, 1)
      for (int k = col; k < nb; k += ncol) {
        const size_t q0 = banded ? (size_t)b->start[k] : 0;
        const size_t q1 = banded ? (size_t)b->start[k + 1] : n;
        for (size_t q = q0; q < q1; q++) {
          const size_t p = banded ? (size_t)b->idx[q] : q;
          if (!dense[p])
            continue;
          if (ext) {
            if (sm)
              add_parts(ws, sm, p, mass[p]);                 /* sum w m */
            add_parts(ws, acc, p, mass[p] * f[p]);           /* sum w m f */
            continue;
          }
          const int e = ws->unit[p];
          if (sm)
            sm[e] += mass[p];                                /* sum m */
          acc[e] += mass[p] * f[p];                          /* sum m f */
        }
      }
    }
  }
}

void mpm_nonlocal_average(mpm_nonlocal *ws, size_t n, const double *mass, const double *g,
                          const unsigned char *dense)
{
  const size_t nu = ws->grid.nu;
  unit_sums(ws, n, mass, g, dense, ws->sm, ws->smg);
#pragma omp parallel for schedule(static) if (nu >= 256)
  for (size_t e = 0; e < nu; e++)
    ws->ge[e] = ws->sm[e] > 0.0 ? ws->smg[e] / ws->sm[e] : 0.0;  /* g_e */
}

void mpm_nonlocal_laplacian(mpm_nonlocal *ws)
{
  mpm_nonlocal_grid_laplacian(&ws->grid, ws->sm, ws->ge, ws->lap);
}

/* H(q) = ((q + c)^3/2 - (q - c)^3/2) / c without cancellation:
 * ((q + c)^3 - (q - c)^3) / (c ((q + c)^3/2 + (q - c)^3/2)); 3 sqrt(q) at c = 0. */
static double h_diff(double q, double c)
{
  double qm = q - c > 0.0 ? q - c : 0.0, qp = q + c > 0.0 ? q + c : 0.0;
  double den = qp * sqrt(qp) + qm * sqrt(qm);
  return den > 0.0 ? (6.0 * q * q + 2.0 * c * c) / den : 0.0;    /* q = c = 0: 0 */
}

double mpm_nonlocal_mean_isqrt(double p0, double a, double c)
{
  a = fabs(a);
  c = fabs(c);
  if (c > a) {                                        /* a: the larger half-range */
    double t = a;
    a = c;
    c = t;
  }
  if (a <= 1e-3 * p0)                                 /* Taylor; next term < 6e-14 */
    return (1.0 + (a * a + c * c) / (8.0 * p0 * p0)) / sqrt(p0);
  /* (1/4) int int q^-1/2 ds dt = (1/(3ac)) [sum of +-(p0 +- a +- c)^3/2]
   *                           = (H(p0 + a) - H(p0 - a)) / (3a) */
  return (h_diff(p0 + a, c) - h_diff(p0 - a, c)) / (3.0 * a);
}

/* The 3D mean of q^-1/2 (mpm_nonlocal_mean_isqrt3) as
 *   (Phi(p0 + a) - Phi(p0 - a)) / (2a),  Phi(q) = int M2(q; b, c) dq,
 * M2 the square's mean of mpm_nonlocal_mean_isqrt (the cube's mean is the
 * mean over s of the square's means at q = p0 + a s). With F = q^5/2,
 *   Phi(q) = (2 / (15 b c)) sum_{+-,+-} (+-)(+-) F(q +- b +- c),
 * the difference in c taken without cancellation as in h_diff,
 *   F(x + c) - F(x - c) = c (10 x^4 + 20 x^2 c^2 + 2 c^4) / ((x + c)^5/2 + (x - c)^5/2),
 * and the one in b directly where b > 1e-3 q; where b <= 1e-3 q, the
 * expansion of the central differences, Phi(q) = 2 q^1/2 - (b^2 + c^2) /
 * (12 q^3/2) (the next term (b, c)^4 / q^7/2), and with b = c = 0 (the
 * segment) 2 q^1/2 itself, also at q = 0, the end a free surface's limiter
 * puts the range at. */
static double f5_diff(double x, double c)      /* (F(x + c) - F(x - c)) / c */
{
  const double xm = x - c > 0.0 ? x - c : 0.0, xp = x + c > 0.0 ? x + c : 0.0;
  const double den = xp * xp * sqrt(xp) + xm * xm * sqrt(xm);
  const double x2 = x * x, c2 = c * c;
  return den > 0.0 ? (10.0 * x2 * x2 + 20.0 * x2 * c2 + 2.0 * c2 * c2) / den : 0.0;
}

static double phi3(double q, double b, double c)
{
  q = q > 0.0 ? q : 0.0;                        /* an ulp below 0 from the limiter: 0 */
  if (b == 0.0)                                 /* c <= b: the segment's 2 q^1/2, q = 0 too */
    return 2.0 * sqrt(q);
  if (b <= 1e-3 * q)
    return 2.0 * sqrt(q) - (b * b + c * c) / (12.0 * q * sqrt(q));
  return 2.0 * (f5_diff(q + b, c) - f5_diff(q - b, c)) / (15.0 * b);
}

double mpm_nonlocal_mean_isqrt3(double p0, double a, double b, double c)
{
  double h[3] = {fabs(a), fabs(b), fabs(c)};
  for (int i = 0; i < 2; i++)                          /* h[0] >= h[1] >= h[2] */
    for (int j = 0; j < 2 - i; j++)
      if (h[j] < h[j + 1]) {
        const double t = h[j];
        h[j] = h[j + 1];
        h[j + 1] = t;
      }
  if (h[0] <= 1e-3 * p0)                               /* Taylor; next term < 1e-12 */
    return (1.0 + (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]) / (8.0 * p0 * p0)) / sqrt(p0);
  return (phi3(p0 + h[0], h[1], h[2]) - phi3(p0 - h[0], h[1], h[2])) / (2.0 * h[0]);
}

/* Pressure of the unit across the face of unit c along axis a towards
 * side s (-1 or +1); 0 if there is none (wall, mesh edge, empty unit). */
static int neighbour_p(const mpm_nonlocal *ws, const int c[3], int a, int s, double *pv)
{
  const mpm_nonlocal_grid *g = &ws->grid;
  int u[3] = {c[0], c[1], c[2]};
  u[a] += s;
  if (u[a] < 0 || u[a] >= g->n[a]) {
    if (g->ghost[2 * a + (s > 0)] != MPM_GHOST_PERIODIC)
      return 0;
    u[a] = (u[a] + g->n[a]) % g->n[a];
  }
  const size_t e = mpm_nonlocal_grid_index(g, u);
  if (!(ws->sm[e] > 0.0))
    return 0;
  *pv = ws->pe[e];
  return 1;
}

/* Half the change of p across unit c along axis a (gradient times half the
 * unit): central, one-sided or 0. */
static double half_change(const mpm_nonlocal *ws, const int c[3], int a, double p0)
{
  double pm = 0.0, pp = 0.0;
  const int hm = neighbour_p(ws, c, a, -1, &pm), hp = neighbour_p(ws, c, a, 1, &pp);
  if (hm && hp)
    return 0.25 * (pp - pm);
  if (hp)
    return 0.5 * (pp - p0);
  if (hm)
    return 0.5 * (p0 - pm);
  return 0.0;
}

void mpm_nonlocal_pressure(mpm_nonlocal *ws, size_t n, const double *mass, const double *p,
                           const unsigned char *dense)
{
  const mpm_nonlocal_grid *g = &ws->grid;
  const size_t nu = g->nu;
  const int D = g->dim;
  unit_sums(ws, n, mass, p, dense, NULL, ws->pe);          /* sum w m p */
#pragma omp parallel for schedule(static) if (nu >= 256)
  for (size_t e = 0; e < nu; e++)
    ws->pe[e] = ws->sm[e] > 0.0 ? ws->pe[e] / ws->sm[e] : 0.0;  /* p_e (sm from average) */
#pragma omp parallel for schedule(static) if (nu > 256)
  for (size_t e = 0; e < nu; e++) {
    const double p0 = ws->pe[e];
    if (!(p0 > 0.0)) {
      ws->isp[e] = 0.0;
      continue;
    }
    const int c[3] = {(int)(e % (size_t)g->n[0]), (int)(e / g->stride[1] % (size_t)g->n[1]),
                      (int)(e / g->stride[2])};
    double hc[3] = {0.0, 0.0, 0.0}, span = 0.0;
    for (int a = 0; a < D; a++) {
      hc[a] = half_change(ws, c, a, p0);
      span = a == 0 ? fabs(hc[a]) : span + fabs(hc[a]);
    }
    if (span > p0)                                      /* limiter: p >= 0 on the unit */
      for (int a = 0; a < D; a++)
        hc[a] *= p0 / span;
    ws->isp[e] = D == 3 ? mpm_nonlocal_mean_isqrt3(p0, hc[0], hc[1], hc[2])
                        : mpm_nonlocal_mean_isqrt(p0, hc[0], hc[1]);
  }
}
