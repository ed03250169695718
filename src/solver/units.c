/* units.c: the per-unit sums of the scheme's options (mesh.dilatation =
 * "unit" and "element": B-bar with one mean stress per unit, the filled
 * units as mixed Q1/P0 elements; docs/model.md), the reordering of the
 * point store by unit rows, and APIC's table of node positions, for either
 * dimension (solver_internal.h). The functions over units take the
 * dimension D as an argument that is a constant where they are inlined (the
 * callers dispatch once), so the loops over axes unroll. The unit sums run
 * in point order on one thread: thread-count free. */
#include "solver/solver_internal.h"

#include <stdlib.h>
#include <string.h>

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
  const mpm_mesh *m = &s->mesh;
  unit_grid g = {.bc = {{cfg->bc.left, cfg->bc.right}, {cfg->bc.bottom, cfg->bc.top},
                        {cfg->bc.front, cfg->bc.back}},
                 .side = {{MPM_OUTLET_LEFT, MPM_OUTLET_RIGHT}, {MPM_OUTLET_BOTTOM, MPM_OUTLET_TOP},
                          {MPM_OUTLET_FRONT, MPM_OUTLET_BACK}}};
  for (int a = 0; a < 3; a++) {
    g.n[a] = m->n[a];
    g.h[a] = m->h[a];
    g.o[a] = a < m->dim ? m->o[a] : 0.0;
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

/* ---- reordering ------------------------------------------------------------ */

int mpm_sim_in_reorder(mpm_sim *s, mpm_err *err)
{
  mpm_points *P = s->pts;
  const size_t n = P->n;
  const mpm_mesh *m = &s->mesh;
  const int a = m->dim - 1;                    /* the band axis */
  const double *y = P->pos[a];
  /* already in row order (a fresh fill, a still run)? A point outside the
   * mesh leaves the order alone: the step reports it. */
  int sorted = 1, prev = 0;
  for (size_t p = 0; p < n; p++) {
    int j;
    double v;
    if (mpm_mesh_locate_axis(m, a, y[p], &j, &v))
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
    mpm_mesh_locate_axis(m, a, y[p], &row[p], &v);
  }
  int rc = mpm_mesh_bands_sort(s->bands, m->n[a], m->periodic[a], 0, 0, n, row, err);  /* one row a band */
  if (rc == MPM_OK)
    mpm_points_permute(P, s->bands->idx, s->scratch);
  return rc;
}

/* ---- B-bar ------------------------------------------------------------------ */

/* With mesh.dilatation = "unit" the units of the mesh carry the volumetric
 * part of the scheme (docs/model.md, "Volumetric strain rate and mean stress
 * per unit"): each point's mean stress s_m = (s_xx + s_yy [+ s_zz])/D acts
 * in point-to-grid as its unit's volume-weighted mean, its tr L is replaced
 * by its unit's volume-weighted mean, and after the update the dense
 * points of a unit share their unit's mean s_m. */

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

/* s->uof[p]: the unit holding point p now, i + nx (j + ny k), -1 outside
 * the mesh. */
static void find_units(mpm_sim *s)
{
  const mpm_points *P = s->pts;
  const size_t n = P->n;
#pragma omp parallel if (n >= 4096)          /* each point its own */
  {
    const mpm_mesh m = s->mesh;              /* each thread's copy: its fields stay in registers */
    const int three = m.dim == 3;
#pragma omp for schedule(static)
    for (size_t p = 0; p < n; p++) {
      const double x[3] = {P->x[p], P->y[p], three ? P->z[p] : 0.0};
      int c[3];
      double l[3];
      s->uof[p] = mpm_mesh_locate(&m, x, c, l) ? -1 : (int)mpm_mesh_unit_index(&m, c);
    }
  }
}

/* What a unit mean averages: the mean stress of the run's dimension D,
 * s_m = (s_xx + s_yy [+ s_zz]) / D (in the plane the in-plane mean), of
 * all points or of the dense ones, or tr L_p over the D axes. */
enum { MEAN_SM, MEAN_SM_DENSE, MEAN_TRL };

/* tr L_p of the velocity gradient of point p kept over the step. */
static inline double trace_L(const mpm_sim *s, size_t p)
{
  if (s->dim == 3)
    return s->L[0][p] + s->L[4][p] + s->L[8][p];
  return s->L[0][p] + s->L[3][p];
}

static inline double mean_value(const mpm_sim *s, size_t p, int what)
{
  return what == MEAN_TRL ? trace_L(s, p) : mpm_sim_in_mean_stress(s, p);
}

/* Units of the run's mesh. */
static size_t unit_count(const mpm_sim *s)
{
  return s->mesh.nunits;
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
#pragma omp parallel for schedule(static) if (nu >= 4096)
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

/* Row r (along axis 0) of the units: filled or not (filled_units_dim). */
EL_INLINE void filled_row(mpm_sim *s, const unit_grid *g, int dim, long r, double vol)
{
  const size_t w = mpm_sim_in_el_width_of(dim);
  const int kz = dim == 3 ? 1 : 0;
  const int k = (int)(r / g->n[1]), j = (int)(r % g->n[1]);
  double *el = s->uel;
  size_t e = (size_t)r * (size_t)g->n[0];
  for (int i = 0; i < g->n[0]; i++, e++) {
    int filled = el[w * e] > 0.0 && s->usum[2 * e] > 0.0;
    for (int c = k - kz; filled && c <= k + kz; c++)
      for (int b = j - 1; filled && b <= j + 1; b++)
        for (int a = i - 1; filled && a <= i + 1; a++)
          filled = neighbour_holds(s, g, dim, (const int[3]){a, b, c});
    el[w * e] = filled ? s->usum[2 * e] / vol : 0.0;
  }
}

/* The parallel loops below call their per-item functions with the
 * dimension as a literal in each branch: the loop body is outlined before
 * it is inlined, so the constant of the caller would not reach it. */

EL_INLINE void filled_units_dim(mpm_sim *s, int dim)
{
  const mpm_points *P = s->pts;
  const unit_grid g = unit_grid_of(s);
  const size_t w = mpm_sim_in_el_width_of(dim);
  double *el = s->uel;
  double vol = 1.0;
  for (int d = 0; d < dim; d++)
    vol *= g.h[d];
  const int nz = dim == 3 ? g.n[2] : 1;
  const size_t nu = unit_count(s);
  for (size_t e = 0; e < nu; e++)
    el[w * e] = 1.0;
  for (size_t p = 0; p < P->n; p++)          /* a unit with a loose point is not filled */
    if (s->uof[p] >= 0 && P->state[p] != MPM_STATE_DENSE)
      el[w * (size_t)s->uof[p]] = 0.0;
  const long rows = (long)nz * g.n[1];
#pragma omp parallel if (nu >= 4096)          /* each unit its own */
  {
    const unit_grid gt = g;                   /* each thread's copy */
#pragma omp for schedule(static)
    for (long r = 0; r < rows; r++) {
      if (dim == 3)
        filled_row(s, &gt, 3, r, vol);
      else
        filled_row(s, &gt, 2, r, vol);
    }
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
  for (int c = 0; c < 1 << dim; c++)
    n[c] = mpm_mesh_node(&s->mesh, at[0] + (c & 1), at[1] + (c >> 1 & 1),
                         dim == 3 ? at[2] + (c >> 2 & 1) : 0);
}

/* The nodal record of node i in a run of dimension dim (mpm_sim_node). */
EL_INLINE double *node_record(const mpm_sim *s, int dim, int i)
{
  return s->nq + (size_t)mpm_sim_node_lanes(dim) * (size_t)i;
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

void mpm_sim_in_element_forces(mpm_sim *s)
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
#pragma omp parallel for schedule(static) if (nu >= 4096)   /* reads usum only */
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
#pragma omp parallel for schedule(static) if (nu >= 4096)
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
#pragma omp parallel if (nu >= 4096)
  {
    const unit_grid gt = g;
#pragma omp for schedule(static)
    for (size_t e = 0; e < nu; e++)
      if (el[w * e] > 0.0)
        el[w * e + 1] = el[w * e] * (dim == 3 ? element_divergence(s, &gt, 3, e)
                                              : element_divergence(s, &gt, 2, e));
  }
}

/* Point p's tr L and volume from its unit's divergence. */
EL_INLINE void dilate_point(mpm_sim *s, int D, size_t p, size_t w, double dt)
{
  const double *el = s->uel;
  const int u = s->uof[p];
  const double tr = trace_L(s, p);
  double div = u < 0 ? tr : s->usum[2 * u + 1];            /* the unit's divergence */
  if (el && u >= 0 && el[w * (size_t)u] > 0.0)
    div = el[w * (size_t)u + 1];
  for (int i = 0; i < D; i++)                                /* L_ii += (div - tr)/D */
    s->L[(D + 1) * i][p] += D == 3 ? (div - tr) / 3.0 : 0.5 * (div - tr);
  s->pts->vol[p] *= mpm_sim_volume_ratio(dt * div);          /* V *= exp(dt tr L) */
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
  const int D = s->dim;
#pragma omp parallel for schedule(static) if (P->n >= 4096)   /* each point its own */
  for (size_t p = 0; p < P->n; p++) {
    if (D == 3)
      dilate_point(s, 3, p, w, dt);
    else
      dilate_point(s, 2, p, w, dt);
  }
}

/* The projection's change of point p's mean stress to its unit's value. */
EL_INLINE void project_point(mpm_sim *s, int dim, size_t p)
{
  mpm_points *P = s->pts;
  const double *el = s->uel;
  const size_t w = mpm_sim_in_el_width_of(dim);
  const int u = s->uof[p];
  if (u < 0 || P->state[p] != MPM_STATE_DENSE)
    return;
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

void mpm_sim_in_unit_project(mpm_sim *s)
{
  if (!s->uof_moved)                         /* the units of x_{n+1} */
    find_units(s);
  unit_means(s, MEAN_SM_DENSE);
  if (s->uel)
    element_slopes(s);
  const size_t n = s->pts->n;
  const int dim = s->dim;
#pragma omp parallel for schedule(static) if (n >= 4096)   /* each point its own */
  for (size_t p = 0; p < n; p++) {
    if (dim == 3)
      project_point(s, 3, p);
    else
      project_point(s, 2, p);
  }
}
