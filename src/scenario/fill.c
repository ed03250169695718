/* fill.c: fill regions with material points (initial state), on a mesh of
 * either dimension.
 *
 * Points sit at the centres of an n x n (x n) sub-grid of every mesh unit
 * whose sub-cell centre lies in the region: V_p = dx dy (dz) / n^D,
 * m_p = rho V_p, uGIMP extent r1 = (dx/2n, 0, 0), r2 = (0, dy/2n, 0),
 * r3 = (0, 0, dz/2n). A fill below rho_c starts disconnected. A lithostatic
 * pre-stress sets sigma_yy = rho g_y (y_top - y) with y_top the top of the
 * fill above the point and sigma_xx = sigma_zz = K0 sigma_yy, K0 = fill.k0,
 * by default nu / (1 - nu) (uniaxial strain); K0 = 1 is isotropic,
 * sigma = -p I. An isotropic pre-stress (`pressure`) sets sigma = -p I
 * ([D-thesis] ch. 4: "initially isotropically compressed"). The
 * pre-stressed material is compressed consistently with the hypoelastic law
 * dp = K drho / rho: rho = rho_fill exp(p / K), so the mass grows. A model
 * with deformation gradients starts from F = Fe of that stress (no
 * rotation; mpm_material_hyper_F_of_stress) and Fp = I. */
#include "scenario/scenario.h"

#include <math.h>
#include <stdlib.h>

#include "material/hyper.h"

static const char axis_name[3] = {'x', 'y', 'z'};

/* Centre of sub-cell i (of n per unit of size d) along an axis from x0:
 * x0 + (i + 1/2) d / n. */
static double sub_centre(double x0, double d, int n, long i)
{
  return x0 + ((double)i + 0.5) * (d / n);
}

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

/* The axis of a 3D disc (a cylinder) and its range along it. */
static int disc_axis(const mpm_fill_config *f, int dim, double *lo, double *hi)
{
  const int a = dim == 3 ? f->axis : 2;
  const double l[3] = {f->xmin, f->ymin, f->zmin}, h[3] = {f->xmax, f->ymax, f->zmax};
  *lo = l[a];
  *hi = h[a];
  return a;
}

int mpm_scenario_inside(const mpm_fill_config *f, int dim, const double x[3])
{
  const int three = dim == 3;
  switch (f->shape) {
  case MPM_FILL_RECTANGLE:
    return x[0] >= f->xmin && x[0] <= f->xmax && x[1] >= f->ymin && x[1] <= f->ymax &&
           (!three || (x[2] >= f->zmin && x[2] <= f->zmax));
  case MPM_FILL_DISC: {
    if (!three) {
      const double ex = x[0] - f->cx, ey = x[1] - f->cy;
      return ex * ex + ey * ey <= f->radius * f->radius;
    }
    double lo, hi;
    const int a = disc_axis(f, dim, &lo, &hi), b = (a + 1) % 3, c = (a + 2) % 3;
    double centre[3] = {f->cx, f->cy, f->cz};
    centre[a] = 0.5 * (lo + hi);
    const double eb = x[b] - centre[b], ec = x[c] - centre[c];
    return x[a] >= lo && x[a] <= hi &&                /* its ends included, exactly */
           eb * eb + ec * ec <= f->radius * f->radius;
  }
  case MPM_FILL_POLYGON:
    return (!three || (x[2] >= f->zmin && x[2] <= f->zmax)) && inside_polygon(f, x[0], x[1]);
  default:
    return 0;
  }
}

/* The region's bounding box, lo[d] .. hi[d] over the mesh's axes. */
static void bounds(const mpm_fill_config *f, int dim, double lo[3], double hi[3])
{
  lo[2] = f->zmin;
  hi[2] = f->zmax;
  if (f->shape == MPM_FILL_POLYGON) {
    lo[0] = hi[0] = f->px[0];
    lo[1] = hi[1] = f->py[0];
    for (int k = 1; k < f->nvert; k++) {
      lo[0] = fmin(lo[0], f->px[k]);
      hi[0] = fmax(hi[0], f->px[k]);
      lo[1] = fmin(lo[1], f->py[k]);
      hi[1] = fmax(hi[1], f->py[k]);
    }
  } else if (f->shape == MPM_FILL_DISC) {
    double l, h;
    const int a = disc_axis(f, dim, &l, &h);
    const double centre[3] = {f->cx, f->cy, f->cz};
    for (int d = 0; d < 3; d++) {
      lo[d] = d == a ? l : centre[d] - f->radius;
      hi[d] = d == a ? h : centre[d] + f->radius;
    }
    if (dim == 2)
      lo[2] = hi[2] = 0.0;
  } else {
    lo[0] = f->xmin;
    hi[0] = f->xmax;
    lo[1] = f->ymin;
    hi[1] = f->ymax;
  }
}

/* MPM_OK if f is a whole region in m (to 1e-9 of a unit, as the input
 * check allows), else MPM_EINPUT with the reason. */
static int check(const mpm_fill_config *f, const mpm_mesh *m, mpm_err *err)
{
  if (f->ppu < 1)
    return mpm_err_set(err, MPM_EINPUT, "fill: ppu = %d must be >= 1", f->ppu);
  if (!(f->density > 0.0) || !isfinite(f->density))
    return mpm_err_set(err, MPM_EINPUT, "fill: density = %g must be > 0 kg/m^3", f->density);
  if (f->shape == MPM_FILL_POLYGON && (f->nvert < 3 || f->nvert > MPM_MAX_POLY))
    return mpm_err_set(err, MPM_EINPUT, "fill: polygon with %d vertices (allowed: 3 ... %d)",
                       f->nvert, MPM_MAX_POLY);
  if (f->shape == MPM_FILL_DISC && m->dim == 3 && (f->axis < 0 || f->axis > 2))
    return mpm_err_set(err, MPM_EINPUT, "fill: cylinder axis = %d must be 0 (x), 1 (y) or 2 (z)",
                       f->axis);
  double lo[3], hi[3];
  bounds(f, m->dim, lo, hi);
  for (int d = 0; d < m->dim; d++) {
    const double tol = 1e-9 * m->h[d];
    if (!(lo[d] <= hi[d]) || !isfinite(lo[d]) || !isfinite(hi[d]))
      return mpm_err_set(err, MPM_EINPUT, "fill: the region's %c range [%g, %g] m is empty",
                         axis_name[d], lo[d], hi[d]);
    if (lo[d] < m->o[d] - tol || hi[d] > m->o[d] + m->len[d] + tol)
      return mpm_err_set(err, MPM_EINPUT, "fill: the region's %c range [%g, %g] m leaves "
                         "the mesh's [%g, %g] m: its points outside the mesh would be lost",
                         axis_name[d], lo[d], hi[d], m->o[d], m->o[d] + m->len[d]);
  }
  return MPM_OK;
}

/* The sub-cells of m along each axis whose centres may lie in f:
 * [i0[d], i1[d]), the bounding box widened by one sub-cell on each side
 * (the inside test decides); the plane's z: [0, 1). */
static void index_range(const mpm_fill_config *f, const mpm_mesh *m, long i0[3], long i1[3])
{
  double lo[3], hi[3];
  bounds(f, m->dim, lo, hi);
  i0[2] = 0;
  i1[2] = 1;
  for (int d = 0; d < m->dim; d++) {
    const double h = m->h[d] / f->ppu;
    const long ns = (long)m->n[d] * f->ppu;
    const long a = (long)floor((lo[d] - m->o[d]) / h) - 1, b = (long)floor((hi[d] - m->o[d]) / h) + 2;
    i0[d] = a < 0 ? 0 : a;
    i1[d] = b > ns ? ns : b;
  }
}

/* The pre-stress of fill f ([DK-silo] 7.1 lithostatic, [D-thesis] ch. 4
 * isotropic; the header) on the points [first, pts->n) just appended: the
 * sub-columns of width h[0] along x (and h[2] along z in 3D), y_top the
 * highest point of the same sub-column plus half a sub-cell. Nothing
 * without a pre-stress; MPM_ENOMEM. */
static int prestress(mpm_points *pts, size_t first, const mpm_fill_config *f,
                     const mpm_material_params *par, double gy, const mpm_mesh *m)
{
  if (!f->lithostatic && !(f->pressure > 0.0))
    return MPM_OK;
  const int n = f->ppu, three = m->dim == 3;
  const double h[3] = {m->dx / n, m->dy / n, m->dz / n};
  const long nc[2] = {(long)m->nx * n, three ? (long)m->nz * n : 1};
  const size_t ncol = (size_t)nc[0] * (size_t)nc[1];
  double *ytop = NULL;
  if (f->lithostatic && !(ytop = malloc(ncol * sizeof *ytop)))
    return MPM_ENOMEM;
  /* the sub-column of a point: along x, and along z in 3D */
#define COLUMN(p)                                                                         \
  ((size_t)floor((pts->x[p] - m->x0) / h[0]) +                                           \
   (three ? (size_t)nc[0] * (size_t)floor((pts->z[p] - m->z0) / h[2]) : 0))
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

/* The elastic state F = Fe of each new point's stress (Fp = I), for a store
 * with deformation gradients; MPM_EINPUT when no elastic state carries it. */
static int elastic_state(mpm_points *pts, size_t first, const mpm_material_params *par,
                         mpm_err *err)
{
  for (size_t p = first; p < pts->n; p++) {
    const mpm_mat3 F = mpm_material_hyper_F_of_stress(par, mpm_points_stress(pts, p));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        pts->F[i][j][p] = F.m[i][j];
        pts->Fp[i][j][p] = i == j ? 1.0 : 0.0;
      }
    if (!isfinite(F.m[0][0] + F.m[1][1] + F.m[2][2]))
      return mpm_err_set(err, MPM_EINPUT, "fill: point %zu: no elastic state gives its "
                         "initial stress", p);
  }
  return MPM_OK;
}

int mpm_scenario_fill(mpm_points *pts, const mpm_mesh *m, const mpm_fill_config *f,
                      const mpm_material_params *par, double gy, mpm_err *err)
{
  if (pts->dim != m->dim)
    return mpm_err_set(err, MPM_EINPUT, "fill: the point store has dimension %d, the mesh %d",
                       pts->dim, m->dim);
  int rc = check(f, m, err);
  if (rc != MPM_OK)
    return rc;
  const int n = f->ppu, D = m->dim;
  const double hs[3] = {m->dx / n, m->dy / n, m->dz / n};
  double vol = hs[0] * hs[1];                              /* V_p = dx dy (dz) / n^D */
  if (D == 3)
    vol *= hs[2];
  const size_t count = mpm_scenario_count(f, m);   /* room for exactly the points to come */
  if (count == 0)
    return mpm_err_set(err, MPM_EINPUT, "fill: region contains no point centre at ppu = %d", n);
  if (mpm_points_reserve(pts, pts->n + count) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory for %zu points", pts->n + count);
  const int state = (par->rho_c > 0.0 && f->density < par->rho_c) ? MPM_STATE_DISCONNECTED
                                                                   : MPM_STATE_DENSE;
  const double v[3] = {f->vx, f->vy, f->vz};
  const size_t first = pts->n;
  long i0[3], i1[3];
  index_range(f, m, i0, i1);
  for (long k = i0[2]; k < i1[2]; k++)
    for (long j = i0[1]; j < i1[1]; j++)
      for (long i = i0[0]; i < i1[0]; i++) {
        const long at[3] = {i, j, k};
        double x[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < D; d++)
          x[d] = sub_centre(m->o[d], m->h[d], n, at[d]);
        if (!mpm_scenario_inside(f, D, x))
          continue;
        size_t p;
        (void)mpm_points_push(pts, &p);                    /* room reserved: cannot fail */
        for (int d = 0; d < D; d++) {
          pts->pos[d][p] = x[d];
          pts->vel[d][p] = v[d];
          pts->ext[d][d][p] = 0.5 * hs[d];
        }
        pts->vol[p] = vol;
        pts->mass[p] = f->density * vol;                   /* m_p = rho V_p */
        pts->state[p] = state;
      }
  if (prestress(pts, first, f, par, gy, m) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory");
  return pts->defgrad ? elastic_state(pts, first, par, err) : MPM_OK;
}

/* ---- counting without filling ---------------------------------------------- */

/* Sub-cell centres of one row along an axis: i in [0, ni) at x0 + (i + 1/2)
 * d / n along it, the other coordinates those of base. */
typedef struct row {
  double x0, d, base[3];
  int n, dim, axis;
  long ni;
  const mpm_fill_config *f;
} row;

/* x_i, the centre of sub-cell i of the row. */
static double row_x(const row *r, long i)
{
  return sub_centre(r->x0, r->d, r->n, i);
}

static int row_inside(const row *r, long i)
{
  double x[3] = {r->base[0], r->base[1], r->base[2]};
  x[r->axis] = row_x(r, i);
  return mpm_scenario_inside(r->f, r->dim, x);
}

/* The first i in [lo, hi) where inside(x_i) differs from `from` (hi if none),
 * for a predicate that changes at most once on [lo, hi). */
static long first_change(const row *r, long lo, long hi, int from)
{
  while (lo < hi) {
    long mid = lo + (hi - lo) / 2;
    if (row_inside(r, mid) == from)
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

/* Points of one row inside f. A box or a cylinder holds one run of centres
 * (the test is monotone on either side of the centre: |x - cx| grows with
 * |i - ic| in floating point too). A polygon's even-odd count changes only
 * where x passes a crossing xc ("x < xc" as in the fill), so the centres
 * before crossing k are a prefix [0, p_k) and the row is inside where an
 * odd number of prefixes hold it (and, for a prism, the row's z is in its
 * range); its rows run along x. */
static long row_count(const row *r)
{
  const mpm_fill_config *f = r->f;
  if (f->shape == MPM_FILL_POLYGON) {
    if (r->dim == 3 && !(r->base[2] >= f->zmin && r->base[2] <= f->zmax))
      return 0;
    double xc[MPM_MAX_POLY];
    long p[MPM_MAX_POLY], count = 0, prev = 0;
    int k = crossings(f, r->base[1], xc);
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
  const double mins[3] = {f->xmin, f->ymin, f->zmin}, maxs[3] = {f->xmax, f->ymax, f->zmax};
  const double centres[3] = {f->cx, f->cy, f->cz};
  const int ax = r->axis;
  double centre = 0.5 * (mins[ax] + maxs[ax]);            /* a box's, or along a cylinder */
  if (f->shape == MPM_FILL_DISC && ax != (r->dim == 3 ? f->axis : 2))
    centre = centres[ax];                                 /* across a disc or a cylinder */
  long ic = first_at_or_after(r, centre);
  long left = ic > 0 && row_inside(r, ic - 1)
                  ? first_change(r, 0, ic, 0)    /* outside ... inside up to ic */
                  : ic;
  long right = ic < r->ni && row_inside(r, ic)
                   ? first_change(r, ic, r->ni, 1)  /* inside from ic ... outside */
                   : ic;
  return right - left;
}

/* The gate of a 3D fill: an axis g and a range [lo, hi] such that a point is
 * inside iff lo <= x_g <= hi and a test of its other two coordinates
 * holds (a box: z; a prism: z; a cylinder: its axis). */
static int gate(const mpm_fill_config *f, double *lo, double *hi)
{
  if (f->shape == MPM_FILL_DISC)
    return disc_axis(f, 3, lo, hi);
  *lo = f->zmin;
  *hi = f->zmax;
  return 2;
}

/* The 3D count as (sub-cells along the gate's axis whose centre passes it)
 * x (the points of one slice across that axis at such a centre), the
 * slice counted in rows: the rows along x (along y for a cylinder along x)
 * of the slice, not of the whole box. The inside test of a point of such a
 * slice does not depend on which passing centre it is at, so the product is
 * the count of the fill exactly, at the cost of one slice: a 4 x 4000 x 4000
 * mesh at 8 points a unit side was 1e9 rows. */
static size_t count_3d(const mpm_fill_config *f, const mpm_mesh *m, const long i0[3],
                       const long i1[3])
{
  double lo, hi;
  const int g = gate(f, &lo, &hi), n = f->ppu;
  long pass = 0, first = -1;
  for (long k = i0[g]; k < i1[g]; k++) {            /* the gate's axis: a few thousand */
    const double c = sub_centre(m->o[g], m->h[g], n, k);
    if (c >= lo && c <= hi) {
      pass++;
      first = first < 0 ? k : first;
    }
  }
  if (pass == 0)
    return 0;
  const int ax = g == 0 ? 1 : 0, across = 3 - g - ax;  /* rows along ax, one per index */
  row r = {.x0 = m->o[ax], .d = m->h[ax], .n = n, .dim = 3, .axis = ax,
           .ni = (long)m->n[ax] * n, .f = f};
  r.base[g] = sub_centre(m->o[g], m->h[g], n, first);
  size_t slice = 0;
  for (long j = i0[across]; j < i1[across]; j++) {
    r.base[across] = sub_centre(m->o[across], m->h[across], n, j);
    slice += (size_t)row_count(&r);
  }
  return (size_t)pass * slice;
}

size_t mpm_scenario_count(const mpm_fill_config *f, const mpm_mesh *m)
{
  const int n = f->ppu;
  if (n < 1 || check(f, m, NULL) != MPM_OK)
    return 0;
  long i0[3], i1[3];
  index_range(f, m, i0, i1);
  if (m->dim == 3)
    return count_3d(f, m, i0, i1);
  row r = {.x0 = m->x0, .d = m->dx, .n = n, .dim = 2, .axis = 0, .ni = (long)m->nx * n, .f = f};
  size_t total = 0;
  for (long j = i0[1]; j < i1[1]; j++) {
    r.base[1] = sub_centre(m->y0, m->dy, n, j);
    total += (size_t)row_count(&r);
  }
  return total;
}
