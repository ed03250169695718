/* fluidity.c: element-averaged granular fluidity and its 5-point Laplacian
 * with ghost rules (MODEL.md section 5 steps 1-2; [DK-silo] §5.2 (i)-(ii),
 * eq. 5.1; boundary conditions on g from [DK-silo] §4 and §6).
 *
 *   g_e   = sum_{p dense} w_pe m_p g_p / sum_{p dense} w_pe m_p
 * w_pe = 1 for the unit containing the centre of p (centre rule) or the
 * fraction of the extent of p lying in unit e (extent rule, [DK-silo]
 * §5.2 (i); the extent is the axis-aligned rectangle of half-widths
 * |r1x| + |r2x|, |r1y| + |r2y|, parts outside the mesh dropped, periodic
 * edges wrapped).
 *   lap_e = (g_E - 2 g_e + g_W)/dx^2 + (g_N - 2 g_e + g_S)/dy^2
 * Ghosts: Neumann g_ghost = g_e (empty neighbour, free edge, frictionless or
 * symmetry wall), Dirichlet g_ghost = -g_e (no-slip wall: g = 0 on the face,
 * midway between the centres), periodic wrap. The stencil and the side rule
 * are those of the unit grid (grid.c), written once for 2 and 3 dimensions;
 * here the edges of the mesh set its rules. */
#include "nonlocal/nonlocal.h"

#include <math.h>
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

void mpm_nonlocal_open_faces(mpm_nonlocal *ws, int edge, int lo, int hi)
{
  const int along = edge <= 1 ? 1 : 0;                 /* rows on the left and right */
  int l[3] = {0, 0, 0}, h[3] = {0, 0, 0};
  l[along] = lo;
  h[along] = hi;
  mpm_nonlocal_grid_open_faces(&ws->grid, edge, l, h);
}

void mpm_nonlocal_walls_neumann(mpm_nonlocal *ws)
{
  for (int k = 0; k < 4; k++)
    if (ws->grid.ghost[k] == MPM_GHOST_DIRICHLET)
      ws->grid.ghost[k] = MPM_GHOST_NEUMANN;
  ws->grid.stamp++;
}

void mpm_nonlocal_held_nodes(const mpm_nonlocal *ws, const mpm_mesh *m, unsigned char *held)
{
  for (int i = 0; i < m->nnodes; i++)
    held[i] = 0;
  const mpm_nonlocal_grid *g = &ws->grid;
  for (int e = 0; e < 4; e++) {
    if (g->ghost[e] != MPM_GHOST_DIRICHLET)
      continue;
    const int len = e <= 1 ? m->ny : m->nx;            /* nodes 0 .. len along the edge */
    const int along = e <= 1 ? 1 : 0;
    for (int a = 0; a <= len; a++) {
      if (e == g->open_face && a >= g->open_lo[along] && a <= g->open_hi[along])
        continue;                                      /* the faces lo .. hi-1 of an open outlet */
      const int i = e == 0 ? 0 : e == 1 ? m->nx : a, j = e == 2 ? 0 : e == 3 ? m->ny : a;
      held[mpm_mesh_node(m, i, j)] = 1;
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
  const size_t nk = ext ? MPM_NONLOCAL_PARTS * cap : 0;
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

static const char *const edge_names[4] = {"left", "right", "bottom", "top"};

/* The unit grid of mesh m with the ghost rules of its four edges; periodic
 * pairs must match the mesh. */
static int set_grid(mpm_nonlocal *ws, const mpm_mesh *m, const int edge[4], mpm_err *err)
{
  int ghost[4];
  for (int k = 0; k < 4; k++) {
    ghost[k] = mpm_nonlocal_ghost_of_bc(edge[k]);
    if (ghost[k] < 0)
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: %s edge has unknown kind %d",
                         edge_names[k], edge[k]);
  }
  int px = ghost[0] == MPM_GHOST_PERIODIC, px2 = ghost[1] == MPM_GHOST_PERIODIC;
  int py = ghost[2] == MPM_GHOST_PERIODIC, py2 = ghost[3] == MPM_GHOST_PERIODIC;
  if (px != px2 || px != (m->periodic_x != 0))
    return mpm_err_set(err, MPM_EINVAL,
                       "nonlocal: left/right periodic edges must match each other and the mesh");
  if (py != py2 || py != (m->periodic_y != 0))
    return mpm_err_set(err, MPM_EINVAL,
                       "nonlocal: bottom/top periodic edges must match each other and the mesh");
  const int n[2] = {m->nx, m->ny};
  const double h[2] = {m->dx, m->dy};
  return mpm_nonlocal_grid_set(&ws->grid, 2, n, h, ghost, err);
}

int mpm_nonlocal_alloc(mpm_nonlocal **out, const mpm_mesh *m, const int edge[4], int rule,
                       size_t cap, mpm_err *err)
{
  *out = NULL;
  if (!mpm_nonlocal_rule_name(rule))
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: unknown averaging rule %d", rule);
  if (m->nx < 1 || m->ny < 1 || !(m->dx > 0.0) || !(m->dy > 0.0))
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: mesh not set up (%d x %d units)",
                       m->nx, m->ny);
  mpm_nonlocal *ws = calloc(1, sizeof *ws);
  if (!ws)
    return mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the workspace");
  int rc = set_grid(ws, m, edge, err);
  if (rc != MPM_OK) {
    mpm_nonlocal_free(ws);
    return rc;
  }
  size_t nu = (size_t)m->nx * (size_t)m->ny;
  ws->nx = m->nx;
  ws->ny = m->ny;
  ws->rule = rule;
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
static int locate_one(mpm_nonlocal *ws, const mpm_mesh *m, size_t p, const double *x,
                      const double *y, const double *const r[4])
{
  int i, j;
  if (mpm_mesh_unit(m, x[p], y[p], &i, &j) != MPM_OK)
    return 1;
  ws->unit[p] = i + ws->nx * j;
  ws->row[p] = j;
  if (ws->rule != MPM_NONLOCAL_EXTENT)
    return 0;
  double xw = x[p], yw = y[p];
  mpm_mesh_wrap(m, &xw, &yw);
  const double hu = (fabs(r[0][p]) + fabs(r[2][p])) * m->idx;   /* |r1x| + |r2x|, in units */
  const double hv = (fabs(r[1][p]) + fabs(r[3][p])) * m->idy;   /* |r1y| + |r2y| */
  if (!(hu <= 0.5 + 1e-12) || !(hv <= 0.5 + 1e-12))
    return 2;
  const double u = fmin(fmax((xw - m->x0) * m->idx - i, 0.0), 1.0);  /* centre in its unit */
  const double v = fmin(fmax((yw - m->y0) * m->idy - j, 0.0), 1.0);
  const int c[3] = {i, j, 0};
  const double at[3] = {u, v, 0.5}, hw[3] = {hu, hv, 0.0};
  mpm_nonlocal_grid_parts(&ws->grid, c, at, hw, ws->part + MPM_NONLOCAL_PARTS * p,
                          ws->w + MPM_NONLOCAL_PARTS * p);
  return 0;
}

int mpm_nonlocal_locate_extents(mpm_nonlocal *ws, const mpm_mesh *m, size_t n, const double *x,
                                const double *y, const double *const r[4], mpm_err *err)
{
  const int ext = ws->rule == MPM_NONLOCAL_EXTENT;
  if (ext && !r)
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: the extent rule needs the point extents");
  int rc = mpm_nonlocal_reserve(ws, n, err);
  if (rc != MPM_OK)
    return rc;
  long bad = (long)n;
#pragma omp parallel for schedule(static) reduction(min : bad) if (n >= 256)
  for (size_t p = 0; p < n; p++)
    if (locate_one(ws, m, p, x, y, r) && (long)p < bad)
      bad = (long)p;
  if (bad < (long)n) {
    const size_t p = (size_t)bad;
    if (locate_one(ws, m, p, x, y, r) == 1)
      return mpm_err_set(err, MPM_EOUTSIDE,
                         "nonlocal: point index %zu at (%.6g, %.6g) m is outside the mesh",
                         p, x[p], y[p]);
    return mpm_err_set(err, MPM_EINVAL,
                       "nonlocal: point index %zu: extent %.6g x %.6g m is wider than a unit", p,
                       2.0 * (fabs(r[0][p]) + fabs(r[2][p])),
                       2.0 * (fabs(r[1][p]) + fabs(r[3][p])));
  }
  /* the rows a point's shares reach: its own, and one either side with extents */
  return mpm_mesh_bands_sort(ws->bands, m->ny, m->periodic_y, ext, ext, n, ws->row, err);
}

int mpm_nonlocal_locate(mpm_nonlocal *ws, const mpm_mesh *m, size_t n, const double *x,
                        const double *y, mpm_err *err)
{
  return mpm_nonlocal_locate_extents(ws, m, n, x, y, NULL, err);
}

/* sum_e w_pe v to the units of point p (extent rule). */
static void add_parts(const mpm_nonlocal *ws, double *acc, size_t p, double v)
{
  const int *part = ws->part + MPM_NONLOCAL_PARTS * p;
  const double *w = ws->w + MPM_NONLOCAL_PARTS * p;
  for (int k = 0; k < MPM_NONLOCAL_PARTS; k++)
    if (w[k] > 0.0)
      acc[part[k]] += w[k] * v;
}

double mpm_nonlocal_point_mean(const mpm_nonlocal *ws, const double *f, size_t p)
{
  return mpm_nonlocal_grid_parts_mean(ws->sm, f, ws->part + MPM_NONLOCAL_PARTS * p,
                                      ws->w + MPM_NONLOCAL_PARTS * p, MPM_NONLOCAL_PARTS);
}

/* acc[e] += w_pe m_p f_p (and, when sm is not NULL, sm[e] += w_pe m_p) over
 * the dense points, after zeroing both: band by band, each colour's bands on
 * all threads, in point order within a band (thread-count free); in point
 * order when the bands are not those of these n points. */
static void unit_sums(mpm_nonlocal *ws, size_t n, const double *mass, const double *f,
                      const unsigned char *dense, double *sm, double *acc)
{
  const size_t nu = (size_t)ws->nx * (size_t)ws->ny;
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
  const size_t nu = (size_t)ws->nx * (size_t)ws->ny;
  unit_sums(ws, n, mass, g, dense, ws->sm, ws->smg);
#pragma omp parallel for schedule(static) if (nu >= 256)
  for (size_t e = 0; e < nu; e++)
    ws->ge[e] = ws->sm[e] > 0.0 ? ws->smg[e] / ws->sm[e] : 0.0;  /* g_e */
}

int mpm_nonlocal_side(const mpm_nonlocal *ws, int i, int j, int side, size_t *nb)
{
  const int c[3] = {i, j, 0};
  return mpm_nonlocal_grid_side(&ws->grid, ws->sm, c, (size_t)i + (size_t)ws->nx * (size_t)j,
                                side, nb);
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

/* Pressure of the unit across the face towards (i + di, j + dj); 0 if there
 * is none (wall, mesh edge, empty unit). */
static int neighbour_p(const mpm_nonlocal *ws, int i, int j, int di, int dj, double *pv)
{
  int ii = i + di, jj = j + dj;
  if (ii < 0 || ii >= ws->nx) {
    if (ws->grid.ghost[ii < 0 ? 0 : 1] != MPM_GHOST_PERIODIC)
      return 0;
    ii = (ii + ws->nx) % ws->nx;
  }
  if (jj < 0 || jj >= ws->ny) {
    if (ws->grid.ghost[jj < 0 ? 2 : 3] != MPM_GHOST_PERIODIC)
      return 0;
    jj = (jj + ws->ny) % ws->ny;
  }
  size_t e = (size_t)ii + (size_t)ws->nx * (size_t)jj;
  if (!(ws->sm[e] > 0.0))
    return 0;
  *pv = ws->pe[e];
  return 1;
}

/* Half the change of p across the unit along one direction (gradient times
 * half the unit): central, one-sided or 0. */
static double half_change(const mpm_nonlocal *ws, int i, int j, int di, int dj, double p0)
{
  double pm = 0.0, pp = 0.0;
  int hm = neighbour_p(ws, i, j, -di, -dj, &pm), hp = neighbour_p(ws, i, j, di, dj, &pp);
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
  size_t nu = (size_t)ws->nx * (size_t)ws->ny;
  unit_sums(ws, n, mass, p, dense, NULL, ws->pe);          /* sum w m p */
#pragma omp parallel for schedule(static) if (nu >= 256)
  for (size_t e = 0; e < nu; e++)
    ws->pe[e] = ws->sm[e] > 0.0 ? ws->pe[e] / ws->sm[e] : 0.0;  /* p_e (sm from average) */
  const int nx = ws->nx, ny = ws->ny;
#pragma omp parallel for schedule(static) if ((long)nx * ny > 256)
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      size_t e = (size_t)i + (size_t)nx * (size_t)j;
      double p0 = ws->pe[e];
      if (!(p0 > 0.0)) {
        ws->isp[e] = 0.0;
        continue;
      }
      double a = half_change(ws, i, j, 1, 0, p0), c = half_change(ws, i, j, 0, 1, p0);
      double span = fabs(a) + fabs(c);
      if (span > p0) {                                  /* limiter: p >= 0 on the unit */
        a *= p0 / span;
        c *= p0 / span;
      }
      ws->isp[e] = mpm_nonlocal_mean_isqrt(p0, a, c);
    }
}
