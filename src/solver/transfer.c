/* transfer.c: the weights of the step, the bands of points, the reordering
 * of the point store, and the grid phase (transfer.h; MODEL.md section 2
 * steps 1-3, [DK15] section 3.1).
 *
 * Threads. Point-to-grid adds every point's share to the nodes around it.
 * The points are binned by bands of unit rows (mesh.h, mpm_mesh_bands) deep
 * enough that two bands of one colour never share a node: the bands of one
 * colour run in parallel, the colours one after the other, and every node
 * sums its shares band by band and in point order within a band, whatever
 * the number of threads and whichever thread takes a band. The grid update
 * is independent per node. Results are bitwise independent of the thread
 * count. */
#include "solver/transfer.h"

#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- step 1: weights ------------------------------------------------------ */

/* Room for the located points of n points. */
static int reserve_located(mpm_sim *s, size_t n, mpm_err *err)
{
  if (n <= s->loc_cap && s->loc_i)
    return MPM_OK;
  if (n == 0)
    n = 1;
  int **ints[] = {&s->loc_i, &s->loc_j, &s->loc_n};
  double **reals[] = {&s->loc_u, &s->loc_v};
  for (size_t k = 0; k < sizeof ints / sizeof ints[0]; k++) {
    int *a = realloc(*ints[k], n * sizeof **ints[k]);
    if (!a)
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu located points", n);
    *ints[k] = a;
  }
  for (size_t k = 0; k < sizeof reals / sizeof reals[0]; k++) {
    double *a = realloc(*reals[k], n * sizeof **reals[k]);
    if (!a)
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu located points", n);
    *reals[k] = a;
  }
  s->loc_cap = n;
  return MPM_OK;
}

/* Unit (i, j) and local (u, v) of points [a, b) as mpm_mesh_locate gives
 * them, for the points whose distances from the mesh origin lie in
 * [0, lx] x [0, ly] (on a periodic axis [0, lx): no wrap needed), which
 * periodic wraps and walls keep nearly all points to: one pass without
 * calls or branches, that vectorises. Returns 1 if a point was outside. */
static int locate_inside(mpm_sim *s, size_t a, size_t b)
{
  const mpm_mesh *m = &s->mesh;
  const double *restrict x = s->pts->x, *restrict y = s->pts->y;
  int *restrict li = s->loc_i, *restrict lj = s->loc_j, *restrict ln = s->loc_n;
  double *restrict lu = s->loc_u, *restrict lv = s->loc_v;
  const double x0 = m->x0, y0 = m->y0, lx = m->lx, ly = m->ly, idx = m->idx, idy = m->idy;
  const double x1 = x0 + lx, y1 = y0 + ly;
  const int nx = m->nx, ny = m->ny, px = m->periodic_x, py = m->periodic_y, snx = m->snx;
  int out = 0;
#pragma omp simd reduction(| : out)
  for (size_t p = a; p < b; p++) {
    const double sx = x[p] - x0, sy = y[p] - y0;
    /* the tests of mpm_mesh_axis_locate on each axis, less the wrap */
    const int in = (px ? sx >= 0.0 && sx < lx : x[p] >= x0 && x[p] <= x1) &&
                   (py ? sy >= 0.0 && sy < ly : y[p] >= y0 && y[p] <= y1);
    out |= !in;
    mpm_mesh_axis_unit(in ? sx : 0.0, idx, nx, &li[p], &lu[p]);
    mpm_mesh_axis_unit(in ? sy : 0.0, idy, ny, &lj[p], &lv[p]);
    ln[p] = lj[p] * snx + li[p];              /* storage id of node (i, j) */
  }
  return out;
}

/* Unit (i, j) and local (u, v) of every point; returns the index of the
 * first point outside the mesh, or n. */
static long locate_all(mpm_sim *s)
{
  const mpm_points *P = s->pts;
  const long n = (long)P->n, nc = (n + 255) / 256;
  long first = n;
#pragma omp parallel for schedule(static) reduction(min : first)
  for (long c = 0; c < nc; c++) {
    const long a = 256 * c, b = a + 256 < n ? a + 256 : n;
    if (!locate_inside(s, (size_t)a, (size_t)b))
      continue;
    for (long p = a; p < b; p++) {           /* wraps, and points outside the mesh */
      if (mpm_mesh_locate(&s->mesh, P->x[p], P->y[p], &s->loc_i[p], &s->loc_j[p],
                          &s->loc_u[p], &s->loc_v[p]) && p < first)
        first = p;
      s->loc_n[p] = s->loc_j[p] * s->mesh.snx + s->loc_i[p];
    }
  }
  return first;
}

/* The geometry of the run's units, axis by axis (the plane's third axis a
 * single unit): counts, sizes, origins, the index step of unit e along
 * each axis, the conditions and outlet sides of each axis' two ends (a
 * periodic axis: MPM_BC_PERIODIC at both). */
typedef struct unit_grid {
  int n[3];
  size_t step[3];
  double h[3], o[3];
  int bc[3][2], side[3][2];
} unit_grid;

static unit_grid unit_grid_of(const mpm_sim *s)
{
  const mpm_config *cfg = &s->cfg;
  unit_grid g = {.bc = {{cfg->bc.left, cfg->bc.right}, {cfg->bc.bottom, cfg->bc.top},
                        {cfg->bc.front, cfg->bc.back}},
                 .side = {{MPM_OUTLET_LEFT, MPM_OUTLET_RIGHT}, {MPM_OUTLET_BOTTOM, MPM_OUTLET_TOP},
                          {MPM_OUTLET_FRONT, MPM_OUTLET_BACK}}};
  if (s->dim == 3) {
    const mpm_mesh3 *m = &s->mesh3;
    g.n[0] = m->nx, g.n[1] = m->ny, g.n[2] = m->nz;
    g.h[0] = m->dx, g.h[1] = m->dy, g.h[2] = m->dz;
    g.o[0] = m->x0, g.o[1] = m->y0, g.o[2] = m->z0;
  } else {
    const mpm_mesh *m = &s->mesh;
    g.n[0] = m->nx, g.n[1] = m->ny, g.n[2] = 1;
    g.h[0] = m->dx, g.h[1] = m->dy, g.h[2] = 1.0;
    g.o[0] = m->x0, g.o[1] = m->y0, g.o[2] = 0.0;
  }
  g.step[0] = 1;
  g.step[1] = (size_t)g.n[0];
  g.step[2] = (size_t)g.n[0] * (size_t)g.n[1];
  return g;
}

/* APIC takes a stencil node's nearest periodic image (mpm_sim_in_node_offset):
 * right while every node lies within half a period of its point. A node lies
 * within h + 1 unit of its point, h = |r1| + |r2| (+ |r3| in 3D) along the
 * axis (the corners' reach), which the input check bounds for extents as
 * filled; a convected (CPDI1) extent can outgrow it: then the run stops,
 * naming the point. */
int mpm_sim_in_apic_extents_fit(const mpm_sim *s, mpm_err *err)
{
  const mpm_points *P = s->pts;
  const int dim = s->dim;
  const unit_grid g = unit_grid_of(s);
  const double *const r[3][3] = {{P->r1x, P->r2x, P->r3x}, {P->r1y, P->r2y, P->r3y},
                                 {P->r1z, P->r2z, P->r3z}};
  for (int axis = 0; axis < dim; axis++) {
    if (g.bc[axis][0] != MPM_BC_PERIODIC)
      continue;
    const double unit = g.h[axis], len = g.n[axis] * unit;
    for (size_t p = 0; p < P->n; p++) {
      double h = 0.0;
      for (int v = 0; v < dim; v++)
        h += fabs(r[axis][v][p]);
      if (!(2.0 * (h + unit) < len))
        return mpm_err_set(err, MPM_EINPUT,
                           "point %d: its extent reaches %.3g units along the periodic %c axis "
                           "of %d units at t = %.6g s (allowed with time.transfer = \"apic\": "
                           "less than half the axis minus one unit); a convected (cpdi) "
                           "extent grew: use shape \"ugimp\" or more units", P->id[p],
                           h / unit, "xyz"[axis], g.n[axis], s->t);
    }
  }
  return MPM_OK;
}

int mpm_sim_in_weights_all(mpm_sim *s, mpm_err *err)
{
  const mpm_points *P = s->pts;
  int rc;
  if (s->step % MPM_SIM_REORDER_EVERY == 0 && (rc = mpm_sim_in_reorder(s, err)) != MPM_OK)
    return rc;
  const int *row;
  int reach;
  if (s->located) {
    if ((rc = reserve_located(s, P->n, err)) != MPM_OK)
      return rc;
    const long bad = locate_all(s);
    if (bad < (long)P->n)
      return mpm_err_set(err, MPM_EOUTSIDE,
                         "point %d left the mesh at (%.6g, %.6g) m, t = %.6g s "
                         "(mesh [%g, %g] x [%g, %g] m)", P->id[bad], P->x[bad], P->y[bad],
                         s->t, s->mesh.x0, s->mesh.x0 + s->mesh.lx, s->mesh.y0,
                         s->mesh.y0 + s->mesh.ly);
    row = s->loc_j;
    reach = 0;
  } else {
    if ((rc = mpm_shape_stencil_compute(s->st, s->shape, &s->mesh, P, s->t, err)) != MPM_OK) {
      /* a point "outside" at a non-finite position or extent: say that */
      if (rc == MPM_EOUTSIDE && mpm_sim_check_state(s, s->t, err) != MPM_OK)
        return MPM_ENONFINITE;
      return rc;
    }
    if (s->cfg.time.transfer == MPM_TRANSFER_APIC && s->shape->convect &&
        (rc = mpm_sim_in_apic_extents_fit(s, err)) != MPM_OK)
      return rc;
    row = s->st->row;
    reach = s->st->reach;
  }
  /* node rows j - reach .. j + 1 + reach of a point in unit row j */
  return mpm_mesh_bands_sort(s->bands, s->mesh.ny, s->mesh.periodic_y, reach, reach + 1, P->n, row, err);
}

/* ---- reordering ------------------------------------------------------------ */

int mpm_sim_in_reorder(mpm_sim *s, mpm_err *err)
{
  mpm_points *P = s->pts;
  const size_t n = P->n;
  const mpm_mesh *m = &s->mesh;
  /* already in row order (a fresh fill, a still run)? A point outside the
   * mesh leaves the order alone: the step reports it. */
  int sorted = 1, prev = 0;
  for (size_t p = 0; p < n; p++) {
    int j;
    double v;
    if (mpm_mesh_axis_locate(P->y[p], m->y0, m->ly, m->idy, m->ny, m->periodic_y, &j, &v))
      return MPM_OK;
    sorted &= j >= prev;
    prev = j;
  }
  if (sorted)
    return MPM_OK;
  if (n > s->scap) {
    void *t = realloc(s->scratch, n * sizeof(double));
    if (!t)
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory to reorder %zu points", n);
    s->scratch = t;
    s->scap = n;
  }
  int *row = s->scratch;                       /* unit row of each point */
  for (size_t p = 0; p < n; p++) {
    double v;
    mpm_mesh_axis_locate(P->y[p], m->y0, m->ly, m->idy, m->ny, m->periodic_y, &row[p], &v);
  }
  int rc = mpm_mesh_bands_sort(s->bands, s->mesh.ny, s->mesh.periodic_y, 0, 0, n, row, err);  /* one row a band */
  if (rc == MPM_OK)
    mpm_points_permute(P, s->bands->idx, s->scratch);
  return rc;
}

/* ---- B-bar ------------------------------------------------------------------ */

/* With mesh.dilatation = "unit" the units of the mesh carry the volumetric
 * part of the scheme (docs/model.md, "Volumetric strain rate and mean stress
 * per unit"): each point's in-plane mean stress s_m = (s_xx + s_yy)/2 acts
 * in point-to-grid as its unit's volume-weighted mean, its tr L is replaced
 * by its unit's volume-weighted mean, and after the update the dense
 * points of a unit share their unit's mean s_m. The unit sums run in point
 * order on one thread: thread-count free. */

int mpm_sim_in_node_table(mpm_sim *s, mpm_err *err)
{
  const int dim = s->dim;
  const unit_grid g = unit_grid_of(s);
  int sn[3] = {1, 1, 1};                   /* stored nodes: a periodic axis aliases its last */
  for (int d = 0; d < dim; d++)
    sn[d] = g.n[d] + (g.bc[d][0] == MPM_BC_PERIODIC ? 0 : 1);
  const int nn = sn[0] * sn[1] * sn[2];
  double *xn = malloc((size_t)dim * (size_t)nn * sizeof *xn);
  if (!xn)
    return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the positions of %d nodes", nn);
  for (int i = 0; i < nn; i++) {
    const int idx[3] = {i % sn[0], i / sn[0] % sn[1], i / (sn[0] * sn[1])};
    for (int d = 0; d < dim; d++)
      xn[(size_t)d * (size_t)nn + (size_t)i] = g.o[d] + idx[d] * g.h[d];
  }
  s->xnode = xn;
  return MPM_OK;
}

/* Room for the unit of every point. */
static int reserve_units(mpm_sim *s, mpm_err *err)
{
  const size_t n = s->pts->n ? s->pts->n : 1;
  if (n <= s->ucap)
    return MPM_OK;
  int *u = realloc(s->uof, n * sizeof *u);
  if (!u)
    return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the units of %zu points", n);
  s->uof = u;
  s->ucap = n;
  return MPM_OK;
}

void mpm_sim_in_boxes(const mpm_sim *s, int *unit)
{
  const mpm_points *P = s->pts;
  const mpm_mesh3 *m = &s->mesh3;
  for (size_t p = 0; p < P->n; p++) {
    const double x[3] = {P->x[p], P->y[p], P->z[p]};
    int u[3];
    double l[3];
    unit[p] = mpm_mesh3_locate(m, x, u, l) ? -1 : u[0] + m->nx * (u[1] + m->ny * u[2]);
  }
}

/* s->uof[p]: the unit holding point p now, -1 outside the mesh (3D: the
 * box, i + nx (j + ny k)). */
static void find_units(mpm_sim *s)
{
  const mpm_points *P = s->pts;
  if (s->dim == 3) {
    mpm_sim_in_boxes(s, s->uof);
    return;
  }
  const mpm_mesh m = s->mesh;             /* a copy: its fields stay in registers */
  for (size_t p = 0; p < P->n; p++) {
    int i, j;
    double u, v;
    s->uof[p] = mpm_mesh_locate(&m, P->x[p], P->y[p], &i, &j, &u, &v) ? -1 : i + m.nx * j;
  }
}

/* What a unit mean averages: the mean stress of the run's dimension D,
 * s_m = (s_xx + s_yy [+ s_zz]) / D (in the plane the in-plane mean), of
 * all points or of the dense ones, or tr L_p over the D axes. */
enum { MEAN_SM, MEAN_SM_DENSE, MEAN_TRL };

/* The velocity gradient of point p kept over the step: the plane's per-point
 * arrays, or the 3D step's rows of 9 (mpm_sim_in_l3). */
static inline double trace_L(const mpm_sim *s, size_t p)
{
  if (s->dim == 3) {
    const double *L = mpm_sim_in_l3(s) + 9 * p;
    return L[0] + L[4] + L[8];
  }
  return s->lxx[p] + s->lyy[p];
}

static inline double mean_value(const mpm_sim *s, size_t p, int what)
{
  return what == MEAN_TRL ? trace_L(s, p) : mpm_sim_in_mean_stress(s, p);
}

/* Units of the run's mesh. */
static size_t unit_count(const mpm_sim *s)
{
  if (s->dim == 3)
    return (size_t)s->mesh3.nx * (size_t)s->mesh3.ny * (size_t)s->mesh3.nz;
  return (size_t)s->mesh.nx * (size_t)s->mesh.ny;
}

/* s->usum[2u + 1] = sum V_p f_p / sum V_p over the points of unit u
 * (s->uof) that take part (the dense ones for MEAN_SM_DENSE), s->usum[2u]
 * = sum V_p; both 0 for a unit without such points. Inlined at each call,
 * where `what` is a constant. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void unit_means(mpm_sim *s, int what)
{
  const mpm_points *P = s->pts;
  const size_t nu = unit_count(s);
  double *us = s->usum;
  memset(us, 0, 2 * nu * sizeof *us);
  for (size_t p = 0; p < P->n; p++) {
    const int u = s->uof[p];
    if (u < 0 || (what == MEAN_SM_DENSE && P->state[p] != MPM_STATE_DENSE))
      continue;
    us[2 * u] += P->vol[p];
    us[2 * u + 1] += P->vol[p] * mean_value(s, p, what);
  }
  for (size_t e = 0; e < nu; e++)
    if (us[2 * e] > 0.0)
      us[2 * e + 1] /= us[2 * e];
}

/* mesh.dilatation = "element": the filled units act as mixed Q1/P0
 * elements for the volumetric part (docs/model.md). A unit is filled when
 * its points are all dense and each of its 3^D - 1 neighbours holds a point
 * or lies beyond a closed edge or face (a wall without the outlet; periodic
 * axes wrap). With w = 1 + 2D values per unit (mpm_sim_in_el_width),
 * s->uel[w e] is the fill fraction phi = sum V_p / V_e of a filled unit, 0
 * of any other; [w e + 1 .. w e + D] the centroid and [w e + D + 1 .. w e +
 * 2D] the slope of its dense points' mean stress field (found before
 * point-to-grid and again at the projection), [w e + 1] in between its rate
 * phi div_e. The functions below take the dimension D as an argument that
 * is a constant where they are inlined (the callers dispatch once), so the
 * loops over axes unroll. */

#if defined(__GNUC__)
#define EL_INLINE static inline __attribute__((always_inline))
#else
#define EL_INLINE static inline
#endif

/* The places of unit e along the D axes. */
EL_INLINE void unit_places(const unit_grid *g, size_t e, int dim, int at[3])
{
  at[0] = (int)(e % (size_t)g->n[0]);
  at[1] = (int)(e / g->step[1] % (size_t)g->n[1]);
  at[2] = dim == 3 ? (int)(e / g->step[2]) : 0;
}

/* Unit at places u[0 .. D-1] (any integers) holds a point, or lies beyond a
 * closed edge or face. */
EL_INLINE int neighbour_holds(const mpm_sim *s, const unit_grid *g, int dim, const int u[3])
{
  size_t e = 0;
  for (int d = 0; d < dim; d++) {
    int a = u[d];
    if (a < 0 || a >= g->n[d]) {
      const int hi = a >= 0, bc = g->bc[d][hi];
      if (bc != MPM_BC_PERIODIC)              /* beyond an edge */
        return bc != MPM_BC_FREE && s->cfg.outlet.edge != g->side[d][hi];
      a = (a + g->n[d]) % g->n[d];
    }
    e += (size_t)a * g->step[d];
  }
  return s->usum[2 * e] > 0.0;
}

EL_INLINE void filled_units_dim(mpm_sim *s, int dim)
{
  const mpm_points *P = s->pts;
  const unit_grid g = unit_grid_of(s);
  const size_t w = mpm_sim_in_el_width_of(dim);
  double *el = s->uel;
  double vol = 1.0;
  for (int d = 0; d < dim; d++)
    vol *= g.h[d];
  const int nz = dim == 3 ? g.n[2] : 1, kz = dim == 3 ? 1 : 0;
  const size_t nu = unit_count(s);
  for (size_t e = 0; e < nu; e++)
    el[w * e] = 1.0;
  for (size_t p = 0; p < P->n; p++)          /* a unit with a loose point is not filled */
    if (s->uof[p] >= 0 && P->state[p] != MPM_STATE_DENSE)
      el[w * (size_t)s->uof[p]] = 0.0;
  size_t e = 0;
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < g.n[1]; j++)
      for (int i = 0; i < g.n[0]; i++, e++) {
        int filled = el[w * e] > 0.0 && s->usum[2 * e] > 0.0;
        for (int c = k - kz; filled && c <= k + kz; c++)
          for (int b = j - 1; filled && b <= j + 1; b++)
            for (int a = i - 1; filled && a <= i + 1; a++)
              filled = neighbour_holds(s, &g, dim, (const int[3]){a, b, c});
        el[w * e] = filled ? s->usum[2 * e] / vol : 0.0;
      }
}

static void filled_units(mpm_sim *s)
{
  if (s->dim == 3)
    filled_units_dim(s, 3);
  else
    filled_units_dim(s, 2);
}

/* The 2^D corner nodes of unit e, corner c offset by bit d of c along axis
 * d (in the plane (i,j), (i+1,j), (i,j+1), (i+1,j+1)). */
EL_INLINE void unit_corners(const mpm_sim *s, const unit_grid *g, int dim, size_t e, int n[8])
{
  int at[3];
  unit_places(g, e, dim, at);
  if (dim == 2)
    for (int c = 0; c < 4; c++)
      n[c] = mpm_mesh_node(&s->mesh, at[0] + (c & 1), at[1] + (c >> 1 & 1));
  else
    for (int c = 0; c < 8; c++)
      n[c] = mpm_mesh3_node(&s->mesh3, at[0] + (c & 1), at[1] + (c >> 1 & 1), at[2] + (c >> 2 & 1));
}

/* The nodal record of node i in a run of dimension D: its 2D lanes. */
EL_INLINE double *node_record(const mpm_sim *s, int dim, int i)
{
  return dim == 3 ? s->nq3[i] : s->nq[i];
}

/* |int_e dN_c/dx_d dV| over a unit, the same for every corner (its sign
 * the corner's side along d): the face normal to d over 2^(D-1) (plane:
 * dy/2 for d = x). */
EL_INLINE double face_share(const unit_grid *g, int dim, int d)
{
  double a = dim == 3 ? 0.25 : 0.5;
  for (int q = 0; q < dim; q++)
    if (q != d)
      a *= g->h[q];
  return a;
}

/* The Q1/P0 share of point-to-grid: f_i += -P_e int_e grad N_i dV over
 * every filled unit e (P_e in s->usum, element_centre_values), on the force
 * lanes D .. 2D-1 of the nodal records. Unit by unit on one thread:
 * thread-count free. */
EL_INLINE void element_forces_dim(mpm_sim *s, int dim)
{
  const unit_grid g = unit_grid_of(s);
  const size_t w = mpm_sim_in_el_width_of(dim), nu = unit_count(s);
  const int nc = 1 << dim;
  double share[3];
  for (int d = 0; d < dim; d++)
    share[d] = face_share(&g, dim, d);
  for (size_t e = 0; e < nu; e++) {
    if (!(s->uel[w * e] > 0.0))
      continue;
    int n[8];
    unit_corners(s, &g, dim, e, n);
    const double sb = s->usum[2 * e + 1];
    for (int c = 0; c < nc; c++) {
      double *q = node_record(s, dim, n[c]);
      for (int d = 0; d < dim; d++)
        q[dim + d] -= sb * (c >> d & 1 ? 1.0 : -1.0) * share[d];
    }
  }
}

static void element_forces(mpm_sim *s)
{
  if (s->dim == 3)
    element_forces_dim(s, 3);
  else
    element_forces_dim(s, 2);
}

/* The divergence of the grid velocity averaged over filled unit e,
 * (1 / V_e) sum_i v_i . int_e grad N_i dV: per axis the corners of the
 * upper side minus those of the lower, over 2^(D-1) h_d. */
EL_INLINE double element_divergence(const mpm_sim *s, const unit_grid *g, int dim, size_t e)
{
  int n[8];
  unit_corners(s, g, dim, e, n);
  const int nc = 1 << dim;
  double div = 0.0;
  for (int d = 0; d < dim; d++) {
    double t = 0.0;
    for (int c = 0; c < nc; c++)
      if (c >> d & 1)
        t += node_record(s, dim, n[c])[d];
    for (int c = 0; c < nc; c++)
      if (!(c >> d & 1))
        t -= node_record(s, dim, n[c])[d];
    div += t / ((double)(nc / 2) * g->h[d]);
  }
  return div;
}

/* minmod: the smaller of two slopes of one sign, else 0. */
static inline double minmod(double a, double b)
{
  return a * b <= 0.0 ? 0.0 : (fabs(a) < fabs(b) ? a : b);
}

/* Slope of the unit means along axis d at unit e (k its place on the axis):
 * minmod of the two one-sided differences to the neighbours that hold dense
 * points (periodic axes wrap); 0 beside a unit without any. Against a wall
 * the field goes on: the one difference inside; against a symmetry line it
 * is even: 0. */
static double mean_slope(const mpm_sim *s, const unit_grid *g, size_t e, int d, int k)
{
  const double *us = s->usum;
  const int n = g->n[d];
  const size_t step = g->step[d], span = step * (size_t)n;
  const double h = g->h[d];
  size_t lo = e - step, hi = e + step;
  if (k == 0 || k == n - 1) {
    const int bc = g->bc[d][k != 0];
    if (bc != MPM_BC_PERIODIC) {
      if (n < 2 || bc == MPM_BC_SYMMETRY || bc == MPM_BC_FREE)
        return 0.0;
      const size_t in = k == 0 ? hi : lo;
      if (!(us[2 * in] > 0.0))
        return 0.0;
      return (k == 0 ? us[2 * in + 1] - us[2 * e + 1] : us[2 * e + 1] - us[2 * in + 1]) / h;
    }
    if (n < 3)
      return 0.0;
    if (k == 0)
      lo = e + span - step;
    else
      hi = e + step - span;
  }
  if (!(us[2 * lo] > 0.0 && us[2 * hi] > 0.0))
    return 0.0;
  return minmod(us[2 * e + 1] - us[2 * lo + 1], us[2 * hi + 1] - us[2 * e + 1]) / h;
}

/* The coordinates of point p over the D axes. */
EL_INLINE void point_at(const mpm_points *P, size_t p, int dim, double x[3])
{
  x[0] = P->x[p];
  x[1] = P->y[p];
  x[2] = dim == 3 ? P->z[p] : 0.0;
}

/* "element": the mean stress field of the units reaches the points as a
 * limited linear one about each unit's centroid of dense points (volume-
 * weighted), so the unit means stay what they were. */
EL_INLINE void element_slopes_dim(mpm_sim *s, int dim)
{
  const mpm_points *P = s->pts;
  const unit_grid g = unit_grid_of(s);
  const size_t w = mpm_sim_in_el_width_of(dim), nu = unit_count(s);
  double *el = s->uel;
  for (size_t e = 0; e < nu; e++)
    for (int d = 0; d < dim; d++)
      el[w * e + 1 + (size_t)d] = 0.0;
  for (size_t p = 0; p < P->n; p++) {
    const int u = s->uof[p];
    if (u < 0 || P->state[p] != MPM_STATE_DENSE)
      continue;
    double x[3];
    point_at(P, p, dim, x);
    for (int d = 0; d < dim; d++)
      el[w * (size_t)u + 1 + (size_t)d] += P->vol[p] * x[d];
  }
  for (size_t e = 0; e < nu; e++) {
    const double v = s->usum[2 * e];
    if (!(v > 0.0))
      continue;
    int at[3];
    unit_places(&g, e, dim, at);
    for (int d = 0; d < dim; d++)
      el[w * e + 1 + (size_t)d] /= v;
    for (int d = 0; d < dim; d++)
      el[w * e + 1 + (size_t)(dim + d)] = mean_slope(s, &g, e, d, at[d]);
  }
}

static void element_slopes(mpm_sim *s)
{
  if (s->dim == 3)
    element_slopes_dim(s, 3);
  else
    element_slopes_dim(s, 2);
}

/* G_e . (x - c_e) for unit values f = s->uel + w e and a point x, the sum
 * in axis order. */
EL_INLINE double slope_offset(const double *f, int dim, const double x[3])
{
  double t = f[1 + dim] * (x[0] - f[1]);
  for (int d = 1; d < dim; d++)
    t += f[1 + dim + d] * (x[d] - f[1 + d]);
  return t;
}

/* The mean stress a filled unit acts with: the value of its points' linear
 * field (slope G_e about their centroid c_e, the points' mean m_e there) at
 * the unit's centre, m_e - G_e . (c_e - centre). The Q1/P0 element's
 * pressure is its mean over the whole unit, which is the centre value of a
 * linear field; the points' mean is its value where the points are (in a
 * floor unit the material never reached, 2.5 mm higher). G_e and c_e are
 * those the last projection used, found again from the points (a run
 * resumed from a checkpoint continues bitwise). */
static void element_centre_values(mpm_sim *s)
{
  const int dim = s->dim;
  const unit_grid g = unit_grid_of(s);
  const size_t w = mpm_sim_in_el_width(s), nu = unit_count(s);
  for (size_t e = 0; e < nu; e++) {
    const double *f = s->uel + w * e;
    if (!(f[0] > 0.0))
      continue;
    int at[3];
    unit_places(&g, e, dim, at);
    double c[3] = {0.0, 0.0, 0.0};             /* the unit's centre */
    for (int d = 0; d < dim; d++)
      c[d] = g.o[d] + ((double)at[d] + 0.5) * g.h[d];
    s->usum[2 * e + 1] += slope_offset(f, dim, c);    /* m_e - G_e . (c_e - centre) */
  }
}

int mpm_sim_in_units_moved(mpm_sim *s, mpm_err *err)
{
  const int rc = reserve_units(s, err);
  if (rc == MPM_OK) {
    find_units(s);
    s->uof_moved = 1;
  }
  return rc;
}

int mpm_sim_in_unit_stress(mpm_sim *s, mpm_err *err)
{
  int rc = reserve_units(s, err);
  if (rc != MPM_OK)
    return rc;
  find_units(s);                             /* the units of x_n */
  s->uof_moved = 0;
  if (s->uel) {                              /* the slopes of the dense points' field */
    unit_means(s, MEAN_SM_DENSE);
    element_slopes(s);
  }
  unit_means(s, MEAN_SM);
  if (s->uel) {
    filled_units(s);
    element_centre_values(s);
  }
  return MPM_OK;
}

/* A filled unit's rate phi div_e in s->uel[w e + 1], once per unit. */
EL_INLINE void element_rates_dim(mpm_sim *s, int dim)
{
  const unit_grid g = unit_grid_of(s);
  const size_t w = mpm_sim_in_el_width_of(dim), nu = unit_count(s);
  double *el = s->uel;
  for (size_t e = 0; e < nu; e++)
    if (el[w * e] > 0.0)
      el[w * e + 1] = el[w * e] * element_divergence(s, &g, dim, e);
}

void mpm_sim_in_unit_dilatation(mpm_sim *s)
{
  mpm_points *P = s->pts;
  unit_means(s, MEAN_TRL);
  double *el = s->uel;
  const size_t w = mpm_sim_in_el_width(s);
  if (el && s->dim == 3)
    element_rates_dim(s, 3);
  else if (el)
    element_rates_dim(s, 2);
  const double dt = s->dt;
  double *L3 = s->dim == 3 ? mpm_sim_in_l3(s) : NULL;
  for (size_t p = 0; p < P->n; p++) {
    const int u = s->uof[p];
    const double tr = trace_L(s, p);
    double div = u < 0 ? tr : s->usum[2 * u + 1];          /* the unit's divergence */
    if (el && u >= 0 && el[w * (size_t)u] > 0.0)
      div = el[w * (size_t)u + 1];
    if (L3) {                                                /* L_ii += (div - tr)/D */
      for (int i = 0; i < 3; i++)
        L3[9 * p + 4 * i] += (div - tr) / 3.0;
    } else {
      s->lxx[p] += 0.5 * (div - tr);
      s->lyy[p] += 0.5 * (div - tr);
    }
    P->vol[p] *= mpm_sim_volume_ratio(dt * div);             /* V *= exp(dt tr L) */
  }
}

/* The projection's change of point p's mean stress to its unit's value. */
EL_INLINE void project_dim(mpm_sim *s, int dim)
{
  mpm_points *P = s->pts;
  const double *el = s->uel;
  const size_t w = mpm_sim_in_el_width_of(dim);
  for (size_t p = 0; p < P->n; p++) {
    const int u = s->uof[p];
    if (u < 0 || P->state[p] != MPM_STATE_DENSE)
      continue;
    double d = s->usum[2 * u + 1] - mpm_sim_in_mean_stress(s, p);
    if (el) {
      double x[3];
      point_at(P, p, dim, x);
      d += slope_offset(el + w * (size_t)u, dim, x);
    }
    P->sxx[p] += d;
    P->syy[p] += d;
    if (dim == 3)
      P->szz[p] += d;
  }
}

void mpm_sim_in_unit_project(mpm_sim *s)
{
  if (!s->uof_moved)                         /* the units of x_{n+1} */
    find_units(s);
  unit_means(s, MEAN_SM_DENSE);
  if (s->uel)
    element_slopes(s);
  if (s->dim == 3)
    project_dim(s, 3);
  else
    project_dim(s, 2);
}

/* ---- steps 2-3 ---------------------------------------------------------------- */

/* APIC's share of step 2 for point p: (mv)_i += S m_p C_p (x_i - x_p).
 * Out of line, so that the FLIP loops stay as lean as they were. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void p2g_affine(const mpm_sim *s, double (*restrict nq)[4], size_t p, int c,
                       const int *node, const double *S)
{
  const mpm_points *P = s->pts;
  const double m = P->mass[p];
  const double C[4] = {P->cxx[p], P->cxy[p], P->cyx[p], P->cyy[p]};
  for (int k = 0; k < c; k++) {
    double e[2];
    mpm_sim_in_node_offset(s, node[k], P->x[p], P->y[p], &e[0], &e[1]);
    mpm_tr_p2g_affine2(nq[node[k]], S[k] * m, C, e);
  }
}

/* Step 2 for point p with weights (c, node, S, gx, gy):
 *   m_i += S m_p,  (mv)_i += S m_p v_p,  f_i += -V_p sigma_p . gradS_ip + S m_p b,
 * as one operation on four lanes per node: q_i += S a + dS/dx ax + dS/dy ay
 * with a = m_p (v_x, v_y, b_x, b_y), ax = -V_p (0, 0, s_xx, s_xy),
 * ay = -V_p (0, 0, s_xy, s_yy). With the B-bar dilatation the in-plane
 * mean stress s_m of the point is its unit's mean, or nothing in a filled
 * unit of "element" (el: s->uel, read once per band). With APIC the
 * momentum takes the affine part too, (mv)_i += S m_p C_p (x_i - x_p)
 * ([JSS+15]: it adds no momentum, sum S (x_i - x_p) = 0 for every shape
 * here). */
static inline void p2g_point(const mpm_sim *s, double *restrict nm, double (*restrict nq)[4],
                             size_t p, int c, const int *node, const double *S,
                             const double *gx, const double *gy, double bx, double by, int bbar,
                             const double *el, int apic)
{
  const mpm_points *P = s->pts;
  const double m = P->mass[p], V = P->vol[p];
  double sxx = P->sxx[p], syy = P->syy[p];
  const double sxy = P->sxy[p];
  if (bbar && s->uof[p] >= 0) {             /* s_m -> the unit's mean */
    const double d = mpm_sim_in_bbar_shift(s, el, p);
    sxx += d;
    syy += d;
  }
  const double a[4] = {m * P->vx[p], m * P->vy[p], m * bx, m * by};
  const double ad[2][4] = {{0.0, 0.0, -V * sxx, -V * sxy}, {0.0, 0.0, -V * sxy, -V * syy}};
  const double *const g[2] = {gx, gy};
  mpm_tr_p2g2(nm, nq, c, node, S, g, m, a, ad);
  if (apic)
    p2g_affine(s, nq, p, c, node, S);
}

/* Step 2 for the points of band k with the tests of the options. */
static inline void p2g_points(const mpm_sim *s, int k, int kind, double bx, double by, int bbar,
                              int apic)
{
  const mpm_mesh_bands *b = s->bands;
  double *restrict nm = s->nm;
  double (*restrict nq)[4] = s->nq;
  const double *el = s->uel;
  const int end = b->start[k + 1];
  for (int q = b->start[k]; q < end; q++) {
    const size_t p = (size_t)b->idx[q];
    mpm_sim_in_basis buf;
    const int *node;
    const double *S, *gx, *gy;
    const int c = mpm_sim_in_weights(s, p, kind, &buf, &node, &S, &gx, &gy);
    p2g_point(s, nm, nq, p, c, node, S, gx, gy, bx, by, bbar, el, apic);
  }
}

/* Step 2 for the points of band k; the plain FLIP loop compiled without the
 * B-bar and APIC tests. */
static inline void p2g_band(const mpm_sim *s, int k, int kind, double bx, double by)
{
  const int bbar = s->usum != NULL, apic = s->cfg.time.transfer == MPM_TRANSFER_APIC;
  if (bbar || apic)
    p2g_points(s, k, kind, bx, by, bbar, apic);
  else
    p2g_points(s, k, kind, bx, by, 0, 0);
}

/* Step 3 on node i: boundary conditions, (mv)_i += dt f_i, v_i = (mv)_i/m_i.
 * A wall zeroes the constrained components of (mv)_i and of f_i ([DK15]
 * section 4: momentum fixed, its update suppressed). The acceleration the
 * points receive is the change of nodal velocity over the step,
 * a_i = f_i/m_i + (v_i^bc - v_i^n)/dt, where v_i^n = (mv)_i/m_i as mapped
 * and v_i^bc the same after the wall acted: f_i/m_i on free components (the
 * jump is exactly 0 there) and -v_i^n/dt on constrained ones. With
 * a_i = f_i/m_i = 0 there instead (boundary.wall_acceleration = "zero",
 * [DK15] read literally), a point stopped by a wall would keep its velocity
 * for ever (FLIP only adds increments): its position follows the grid and
 * stays put, but it reports kinetic energy it does not have, and a
 * kinetic-energy stop test never fires; in steady flow along a wall the jump
 * kicks the points beside it every step instead (docs/model.md).
 * With delta shape functions a node lighter than mlight (1e-3 of the mean
 * point mass: the points near it lie within about a thousandth of a unit of
 * its far edge) takes the body force only. Its internal force
 * -V sigma.gradS does not shrink with its weight S, so f_i/m_i grows as 1/S
 * when a stressed point crosses into an empty unit, and that velocity, times
 * gradS, enters L_p: a point's volume overflowed (1e111 m^2) this way at a
 * heap's surface. uGIMP gradients vanish with the weights (mlight = 0).
 * Nodes lighter than mtiny are empty: v_i = a_i = 0. */
static inline void grid_node(mpm_sim *s, int i, double bx, double by, double idt)
{
  const double b[2] = {bx, by};
  mpm_tr_grid_node2(&s->bc, i, s->bc.fix[i] != 0, s->nm[i], s->nq[i], b, s->dt, idt, s->mtiny,
                    s->mlight);
}

/* Step 2 for band k with the weights of the step (a constant kind at each
 * call, so each is compiled for its weights). */
static void p2g_band_of(const mpm_sim *s, int k, int kind, double bx, double by)
{
  switch (kind) {
  case MPM_SIM_IN_Q4:
    p2g_band(s, k, MPM_SIM_IN_Q4, bx, by);
    break;
  case MPM_SIM_IN_ELEMENT:
    p2g_band(s, k, MPM_SIM_IN_ELEMENT, bx, by);
    break;
  default:
    p2g_band(s, k, MPM_SIM_IN_STORED, bx, by);
  }
}

/* Steps 2-3 in one parallel region: clear the nodes, each colour's bands in
 * parallel, the colours in turn, then the grid update by nodes; dim (a
 * constant at each call) picks the plane or the 3D records and kernels. */
static inline void grid_phase(mpm_sim *s, int dim, const double b[3])
{
  const int kind = mpm_sim_in_kind(s);
  const mpm_mesh_bands *bd = s->bands;
  const int nn = dim == 3 ? s->mesh3.nnodes : s->mesh.nnodes;
  const double idt = s->cfg.bc.wall_acceleration == MPM_WALL_ZERO ? 0.0 : 1.0 / s->dt;
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (int i = 0; i < nn; i++) {
      s->nm[i] = 0.0;
      if (dim == 3)
        memset(s->nq3[i], 0, sizeof s->nq3[i]);
      else
        s->nq[i][0] = s->nq[i][1] = s->nq[i][2] = s->nq[i][3] = 0.0;
    }
    for (int col = 0; col < bd->ncolour; col++) {
#pragma omp for schedule(dynamic, 1)
      for (int k = col; k < bd->nb; k += bd->ncolour) {
        if (dim == 3)
          mpm_sim_in_p2g_band3(s, k, b);
        else
          p2g_band_of(s, k, kind, b[0], b[1]);
      }
    }
    if (s->uel) {
#pragma omp single
      element_forces(s);
    }
#pragma omp for schedule(static)
    for (int i = 0; i < nn; i++) {
      if (dim == 3)
        mpm_sim_in_grid_node3(s, i, b, idt);
      else
        grid_node(s, i, b[0], b[1], idt);
    }
  }
}

void mpm_sim_in_grid(mpm_sim *s, double bx, double by)
{
  const double b[3] = {bx, by, 0.0};
  grid_phase(s, 2, b);
}

void mpm_sim_in_grid3(mpm_sim *s, const double b[3])
{
  grid_phase(s, 3, b);
}
