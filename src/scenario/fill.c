/* fill.c: fill regions with material points (initial state).
 *
 * Points sit at the centres of an n x n sub-grid of every mesh unit whose
 * sub-cell centre lies in the region: V_p = dx dy / n^2, m_p = rho V_p,
 * uGIMP extent r1 = (dx/2n, 0), r2 = (0, dy/2n). A lithostatic pre-stress sets
 * sigma_yy = rho g_y (y_top - y) with y_top the top of the fill above the point
 * and sigma_xx = sigma_zz = K0 sigma_yy, K0 = fill.k0, by default nu / (1 - nu)
 * (uniaxial strain); K0 = 1 is isotropic, sigma = -p I.
 * An isotropic pre-stress (`pressure`) sets sigma = -p I ([D-thesis] ch. 4:
 * "initially isotropically compressed").
 * The pre-stressed material is compressed consistently with the hypoelastic
 * law dp = K drho / rho: rho = rho_fill exp(p / K), so the mass grows. */
#include "scenario/scenario.h"
#include "scenario/scenario_internal.h"

#include <math.h>
#include <stdlib.h>

/* x of the sides of polygon f crossed by the horizontal line at y, in xc
 * (room for f->nvert); returns their number. */
static int crossings(const mpm_fill_config *f, double y, double *xc)
{
  int k = 0;
  for (int a = 0, b = f->nvert - 1; a < f->nvert; b = a++) {
    double ya = f->py[a], yb = f->py[b];
    if ((ya > y) != (yb > y))
      xc[k++] = f->px[a] + (y - ya) * (f->px[b] - f->px[a]) / (yb - ya);
  }
  return k;
}

/* Even-odd rule: a ray to +x crosses the polygon boundary an odd number of times. */
static int inside_polygon(const mpm_fill_config *f, double x, double y)
{
  double xc[MPM_MAX_POLY];
  int in = 0, k = crossings(f, y, xc);
  for (int c = 0; c < k; c++)
    if (x < xc[c])
      in = !in;
  return in;
}

int mpm_scenario_inside(const mpm_fill_config *f, double x, double y)
{
  switch (f->shape) {
  case MPM_FILL_RECTANGLE:
    return x >= f->xmin && x <= f->xmax && y >= f->ymin && y <= f->ymax;
  case MPM_FILL_DISC: {
    double ex = x - f->cx, ey = y - f->cy;
    return ex * ex + ey * ey <= f->radius * f->radius;
  }
  case MPM_FILL_POLYGON:
    return inside_polygon(f, x, y);
  default:
    return 0;
  }
}

int mpm_scenario_in_prestress(mpm_points *pts, size_t first, const mpm_fill_config *f,
                              const mpm_material_params *par, double gy, const double o[2],
                              const double h[3], const long nc[2])
{
  if (!f->lithostatic && !(f->pressure > 0.0))
    return MPM_OK;
  const size_t ncol = (size_t)nc[0] * (size_t)nc[1];
  double *ytop = NULL;
  if (f->lithostatic && !(ytop = malloc(ncol * sizeof *ytop)))
    return MPM_ENOMEM;
  /* the sub-column of a point: along x, and along z in 3D */
#define COLUMN(p)                                                                         \
  ((size_t)floor((pts->x[p] - o[0]) / h[0]) +                                            \
   (pts->z ? (size_t)nc[0] * (size_t)floor((pts->z[p] - o[1]) / h[2]) : 0))
  for (size_t c = 0; ytop && c < ncol; c++)
    ytop[c] = -INFINITY;
  for (size_t p = first; ytop && p < pts->n; p++) {
    const size_t c = COLUMN(p);
    if (pts->y[p] > ytop[c])
      ytop[c] = pts->y[p];
  }
  const double k0 = f->k0 > 0.0 ? f->k0 : par->nu / (1.0 - par->nu);  /* K0 */
  for (size_t p = first; p < pts->n; p++) {
    double pr;
    if (ytop) {
      const double syy = f->density * gy * (ytop[COLUMN(p)] + 0.5 * h[1] - pts->y[p]);
      pts->syy[p] = syy;                                    /* gy < 0: compression */
      pts->sxx[p] = pts->szz[p] = k0 * syy;
      pr = -(1.0 + 2.0 * k0) * syy / 3.0;                   /* p = -tr(sigma)/3 */
    } else {
      pts->sxx[p] = pts->syy[p] = pts->szz[p] = -f->pressure; /* sigma = -p I */
      pr = f->pressure;
    }
    pts->mass[p] *= exp(pr / par->K);                       /* rho = rho_fill exp(p/K) */
  }
#undef COLUMN
  free(ytop);
  return MPM_OK;
}

int mpm_scenario_fill(mpm_points *pts, const mpm_mesh *m, const mpm_fill_config *f,
                      const mpm_material_params *par, double gy, mpm_err *err)
{
  int n = f->ppu;
  if (n < 1)
    return mpm_err_set(err, MPM_EINPUT, "fill: ppu = %d must be >= 1", n);
  if (!(f->density > 0.0))
    return mpm_err_set(err, MPM_EINPUT, "fill: density = %g must be > 0 kg/m^3", f->density);
  double hx = m->dx / n, hy = m->dy / n;
  double vol = hx * hy;                                    /* V_p = dx dy / n^2 */
  const size_t count = mpm_scenario_count(f, m);   /* room for exactly the points to come */
  if (mpm_points_reserve(pts, pts->n + count) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory for %zu points", pts->n + count);
  int state = (par->rho_c > 0.0 && f->density < par->rho_c) ? MPM_STATE_DISCONNECTED
                                                             : MPM_STATE_DENSE;
  size_t first = pts->n;
  for (int j = 0; j < m->ny * n; j++) {
    double y = mpm_scenario_in_sub_centre(m->y0, m->dy, n, j);
    for (int i = 0; i < m->nx * n; i++) {
      double x = mpm_scenario_in_sub_centre(m->x0, m->dx, n, i);
      if (!mpm_scenario_inside(f, x, y))
        continue;
      size_t p;
      if (mpm_points_push(pts, &p) != MPM_OK)
        return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory at %zu points", pts->n);
      pts->x[p] = x;
      pts->y[p] = y;
      pts->vx[p] = f->vx;
      pts->vy[p] = f->vy;
      pts->vol[p] = vol;
      pts->mass[p] = f->density * vol;                     /* m_p = rho V_p */
      pts->r1x[p] = 0.5 * hx;
      pts->r2y[p] = 0.5 * hy;
      pts->state[p] = state;
    }
  }
  if (pts->n == first)
    return mpm_err_set(err, MPM_EINPUT, "fill: region contains no point centre at ppu = %d", n);
  const double o[2] = {m->x0, 0.0}, h[3] = {hx, hy, 0.0};
  const long nc[2] = {(long)m->nx * n, 1};
  if (mpm_scenario_in_prestress(pts, first, f, par, gy, o, h, nc) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory");
  return MPM_OK;
}

/* ---- counting without filling ---------------------------------------------- */

/* Sub-cell centres of one row: i in [0, ni) at x0 + (i + 1/2) d / n. */
typedef struct row {
  double x0, d, y;
  int n;
  long ni;
  const mpm_fill_config *f;
} row;

/* x_i, the centre of sub-cell i of the row. */
static double row_x(const row *r, long i)
{
  return mpm_scenario_in_sub_centre(r->x0, r->d, r->n, i);
}

/* The first i in [lo, hi) where inside(x_i) differs from `from` (hi if none),
 * for a predicate that changes at most once on [lo, hi). */
static long first_change(const row *r, long lo, long hi, int from)
{
  while (lo < hi) {
    long mid = lo + (hi - lo) / 2;
    if (mpm_scenario_inside(r->f, row_x(r, mid), r->y) == from)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/* The first i with x_i >= x (ni if none): positions grow with i. */
static long first_at_or_after(const row *r, double x)
{
  long lo = 0, hi = r->ni;
  while (lo < hi) {
    long mid = lo + (hi - lo) / 2;
    if (row_x(r, mid) < x)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

static int cmp_long(const void *a, const void *b)
{
  long x = *(const long *)a, y = *(const long *)b;
  return (x > y) - (x < y);
}

/* Points of one row inside f. A rectangle or a disc holds one run of
 * centres (the test is monotone on either side of the centre: |x - cx|
 * grows with |i - ic| in floating point too). A polygon's even-odd count
 * changes only where x passes a crossing xc ("x < xc" as in the fill), so the
 * centres before crossing k are a prefix [0, p_k) and the row is inside
 * where an odd number of prefixes hold it. */
static long row_count(const row *r)
{
  const mpm_fill_config *f = r->f;
  if (f->shape == MPM_FILL_POLYGON) {
    double xc[MPM_MAX_POLY];
    long p[MPM_MAX_POLY], count = 0, prev = 0;
    int k = crossings(f, r->y, xc);
    for (int c = 0; c < k; c++)
      p[c] = first_at_or_after(r, xc[c]);   /* x_i < xc exactly for i < p */
    qsort(p, (size_t)k, sizeof *p, cmp_long);
    for (int c = 0; c < k; c++) {           /* on [p_{c-1}, p_c): k - c prefixes hold */
      if ((k - c) % 2)
        count += p[c] - prev;
      prev = p[c];
    }
    return count;
  }
  double centre = f->shape == MPM_FILL_DISC ? f->cx : 0.5 * (f->xmin + f->xmax);
  long ic = first_at_or_after(r, centre);
  long left = ic > 0 && mpm_scenario_inside(f, row_x(r, ic - 1), r->y)
                  ? first_change(r, 0, ic, 0)    /* outside ... inside up to ic */
                  : ic;
  long right = ic < r->ni && mpm_scenario_inside(f, row_x(r, ic), r->y)
                   ? first_change(r, ic, r->ni, 1)  /* inside from ic ... outside */
                   : ic;
  return right - left;
}

size_t mpm_scenario_count(const mpm_fill_config *f, const mpm_mesh *m)
{
  const int n = f->ppu;
  if (n < 1)
    return 0;
  row r = {.x0 = m->x0, .d = m->dx, .n = n, .ni = (long)m->nx * n, .f = f};
  size_t total = 0;
  for (long j = 0; j < (long)m->ny * n; j++) {
    r.y = mpm_scenario_in_sub_centre(m->y0, m->dy, n, j);
    total += (size_t)row_count(&r);
  }
  return total;
}
