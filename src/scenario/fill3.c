/* fill3.c: fill regions of a 3D mesh of boxes with material points (initial
 * state of the 3D module).
 *
 * As the 2D fill (fill.c): points sit at the centres of an n x n x n sub-grid
 * of every unit whose sub-cell centre lies in the region (the same sub-cell
 * centre, scenario_internal.h): V_p = dx dy dz / n^3, m_p = rho V_p, uGIMP
 * extent r1 = (dx/2n, 0, 0), r2 = (0, dy/2n, 0), r3 = (0, 0, dz/2n). Regions:
 * an axis-aligned box, a cylinder whose axis is x, y or z, and a prism: a
 * plane polygon extruded along z. The stress starts at zero;
 * mpm_scenario_prestress3 then sets the fill's lithostatic or isotropic
 * pre-stress as the plane fill does (scenario_internal.h), for the
 * hyperelastic model through the elastic deformation F = Fe that carries it. A
 * region must lie in the mesh, periodic axes included: a fill that only covers
 * the mesh's part of it would silently lose material. */
#include <string.h>

#include "scenario/scenario.h"
#include "scenario/scenario_internal.h"
#include "material/hyper.h"

#include <math.h>

static const char axis_name[3] = {'x', 'y', 'z'};

int mpm_scenario_inside3(const mpm_fill3_region *f, const double x[3])
{
  switch (f->shape) {
  case MPM_FILL3_BOX:
    return x[0] >= f->lo[0] && x[0] <= f->hi[0] && x[1] >= f->lo[1] && x[1] <= f->hi[1] &&
           x[2] >= f->lo[2] && x[2] <= f->hi[2];
  case MPM_FILL3_CYLINDER: {
    const int a = f->axis, b = (a + 1) % 3, c = (a + 2) % 3;
    const double eb = x[b] - f->centre[b], ec = x[c] - f->centre[c];
    return fabs(x[a] - f->centre[a]) <= 0.5 * f->length &&
           eb * eb + ec * ec <= f->radius * f->radius;
  }
  case MPM_FILL3_PRISM:
    return x[2] >= f->lo[2] && x[2] <= f->hi[2] && mpm_scenario_inside(f->polygon, x[0], x[1]);
  default:
    return 0;
  }
}

/* The region's bounding box, lo[d] .. hi[d]. */
static void bounds(const mpm_fill3_region *f, double lo[3], double hi[3])
{
  if (f->shape == MPM_FILL3_PRISM) {
    const mpm_fill_config *q = f->polygon;
    lo[0] = hi[0] = q->px[0];
    lo[1] = hi[1] = q->py[0];
    for (int k = 1; k < q->nvert; k++) {
      lo[0] = fmin(lo[0], q->px[k]);
      hi[0] = fmax(hi[0], q->px[k]);
      lo[1] = fmin(lo[1], q->py[k]);
      hi[1] = fmax(hi[1], q->py[k]);
    }
    lo[2] = f->lo[2];
    hi[2] = f->hi[2];
    return;
  }
  for (int d = 0; d < 3; d++) {
    if (f->shape == MPM_FILL3_BOX) {
      lo[d] = f->lo[d];
      hi[d] = f->hi[d];
    } else {
      const double h = d == f->axis ? 0.5 * f->length : f->radius;
      lo[d] = f->centre[d] - h;
      hi[d] = f->centre[d] + h;
    }
  }
}

/* MPM_OK if f is a whole region in m, else MPM_EINPUT with the reason. */
static int check(const mpm_fill3_region *f, const mpm_mesh3 *m, mpm_err *err)
{
  if (f->ppu < 1)
    return mpm_err_set(err, MPM_EINPUT, "fill3: ppu = %d must be >= 1", f->ppu);
  if (!(f->density > 0.0) || !isfinite(f->density))
    return mpm_err_set(err, MPM_EINPUT, "fill3: density = %g must be > 0 kg/m^3", f->density);
  for (int d = 0; d < 3; d++)
    if (!isfinite(f->v[d]))
      return mpm_err_set(err, MPM_EINPUT, "fill3: velocity v%c = %g is not finite",
                         axis_name[d], f->v[d]);
  if (f->shape == MPM_FILL3_BOX) {
    for (int d = 0; d < 3; d++)
      if (!(f->lo[d] < f->hi[d]) || !isfinite(f->lo[d]) || !isfinite(f->hi[d]))
        return mpm_err_set(err, MPM_EINPUT, "fill3: box %c range [%g, %g] m is empty",
                           axis_name[d], f->lo[d], f->hi[d]);
  } else if (f->shape == MPM_FILL3_CYLINDER) {
    if (f->axis < 0 || f->axis > 2)
      return mpm_err_set(err, MPM_EINPUT, "fill3: cylinder axis = %d must be 0 (x), 1 (y) "
                         "or 2 (z)", f->axis);
    if (!(f->radius > 0.0) || !(f->length > 0.0) || !isfinite(f->radius) ||
        !isfinite(f->length))
      return mpm_err_set(err, MPM_EINPUT, "fill3: cylinder radius = %g m and length = %g m "
                         "must be > 0", f->radius, f->length);
    for (int d = 0; d < 3; d++)
      if (!isfinite(f->centre[d]))
        return mpm_err_set(err, MPM_EINPUT, "fill3: cylinder centre %c = %g is not finite",
                           axis_name[d], f->centre[d]);
  } else if (f->shape == MPM_FILL3_PRISM) {
    const mpm_fill_config *q = f->polygon;
    if (!q || q->nvert < 3 || q->nvert > MPM_MAX_POLY)
      return mpm_err_set(err, MPM_EINPUT, "fill3: prism with %d vertices (allowed: 3 ... %d)",
                         q ? q->nvert : 0, MPM_MAX_POLY);
    for (int k = 0; k < q->nvert; k++)
      if (!isfinite(q->px[k]) || !isfinite(q->py[k]))
        return mpm_err_set(err, MPM_EINPUT, "fill3: prism vertex %d is not finite", k);
    if (!(f->lo[2] < f->hi[2]) || !isfinite(f->lo[2]) || !isfinite(f->hi[2]))
      return mpm_err_set(err, MPM_EINPUT, "fill3: prism z range [%g, %g] m is empty", f->lo[2],
                         f->hi[2]);
  } else {
    return mpm_err_set(err, MPM_EINPUT, "fill3: unknown region shape %d", f->shape);
  }
  double lo[3], hi[3];
  bounds(f, lo, hi);
  const double o[3] = {m->x0, m->y0, m->z0}, l[3] = {m->lx, m->ly, m->lz};
  for (int d = 0; d < 3; d++)
    if (lo[d] < o[d] || hi[d] > o[d] + l[d])
      return mpm_err_set(err, MPM_EINPUT, "fill3: the region's %c range [%g, %g] m leaves "
                         "the mesh's [%g, %g] m: its points outside the mesh would be lost",
                         axis_name[d], lo[d], hi[d], o[d], o[d] + l[d]);
  return MPM_OK;
}

/* The sub-cells of m along each axis whose centres may lie in f:
 * [i0[d], i1[d]), the bounding box widened by one sub-cell on each side
 * (the inside test decides). */
static void index_range(const mpm_fill3_region *f, const mpm_mesh3 *m, long i0[3], long i1[3])
{
  double lo[3], hi[3];
  bounds(f, lo, hi);
  const double o[3] = {m->x0, m->y0, m->z0}, du[3] = {m->dx, m->dy, m->dz};
  const long nu[3] = {m->nx, m->ny, m->nz};
  for (int d = 0; d < 3; d++) {
    const double h = du[d] / f->ppu;
    const long ns = nu[d] * f->ppu;
    long a = (long)floor((lo[d] - o[d]) / h) - 1, b = (long)floor((hi[d] - o[d]) / h) + 2;
    i0[d] = a < 0 ? 0 : a;
    i1[d] = b > ns ? ns : b;
  }
}

/* Visit the sub-cell centres of m inside f in the fill's order (x fastest,
 * z slowest); without pts, count them only. */
static size_t visit(const mpm_fill3_region *f, const mpm_mesh3 *m, mpm_points *pts)
{
  const int n = f->ppu;
  long i0[3], i1[3];
  index_range(f, m, i0, i1);
  const double hx = m->dx / n, hy = m->dy / n, hz = m->dz / n;
  const double vol = hx * hy * hz;                         /* V_p = dx dy dz / n^3 */
  size_t count = 0;
  for (long k = i0[2]; k < i1[2]; k++)
    for (long j = i0[1]; j < i1[1]; j++)
      for (long i = i0[0]; i < i1[0]; i++) {
        const double x[3] = {mpm_scenario_in_sub_centre(m->x0, m->dx, n, i),
                             mpm_scenario_in_sub_centre(m->y0, m->dy, n, j),
                             mpm_scenario_in_sub_centre(m->z0, m->dz, n, k)};
        if (!mpm_scenario_inside3(f, x))
          continue;
        count++;
        if (!pts)
          continue;
        size_t p;
        (void)mpm_points_push(pts, &p);                    /* room reserved: cannot fail */
        pts->x[p] = x[0];
        pts->y[p] = x[1];
        pts->z[p] = x[2];
        pts->vx[p] = f->v[0];
        pts->vy[p] = f->v[1];
        pts->vz[p] = f->v[2];
        pts->vol[p] = vol;
        pts->mass[p] = f->density * vol;                   /* m_p = rho V_p */
        pts->r1x[p] = 0.5 * hx;
        pts->r2y[p] = 0.5 * hy;
        pts->r3z[p] = 0.5 * hz;
        pts->state[p] = MPM_STATE_DENSE;
        pts->fxx[p] = pts->fyy[p] = pts->fzz[p] = 1.0;      /* F = Fp = I: the fill's */
        pts->fpxx[p] = pts->fpyy[p] = pts->fpzz[p] = 1.0;   /* natural state */
      }
  return count;
}

size_t mpm_scenario_count3(const mpm_fill3_region *f, const mpm_mesh3 *m)
{
  mpm_err err = {0};
  return check(f, m, &err) == MPM_OK ? visit(f, m, NULL) : 0;
}

int mpm_scenario_fill3(mpm_points *pts, const mpm_mesh3 *m, const mpm_fill3_region *f,
                       mpm_err *err)
{
  if (pts->dim != 3)
    return mpm_err_set(err, MPM_EINPUT, "fill3: the point store has dimension %d; a 3D "
                       "fill needs a store of dimension 3 (mpm_points_alloc_dim)", pts->dim);
  int rc = check(f, m, err);
  if (rc != MPM_OK)
    return rc;
  const size_t count = visit(f, m, NULL);
  if (count == 0)
    return mpm_err_set(err, MPM_EINPUT, "fill3: region contains no point centre at ppu = %d",
                       f->ppu);
  if (mpm_points_reserve(pts, pts->n + count) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill3: out of memory for %zu points", pts->n + count);
  visit(f, m, pts);
  return MPM_OK;
}

int mpm_scenario_prestress3(mpm_points *pts, size_t first, const mpm_mesh3 *m,
                            const mpm_fill_config *f, const mpm_material_params *par, double gy,
                            int hyper, mpm_err *err)
{
  const int n = f->ppu;
  const double o[2] = {m->x0, m->z0}, h[3] = {m->dx / n, m->dy / n, m->dz / n};
  const long nc[2] = {(long)m->nx * n, (long)m->nz * n};
  if (mpm_scenario_in_prestress(pts, first, f, par, gy, o, h, nc) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill3: out of memory for the pre-stress");
  if (!hyper || (!f->lithostatic && !(f->pressure > 0.0)))
    return MPM_OK;
  for (size_t p = first; p < pts->n; p++) {           /* the elastic state of the stress */
    const mpm_mat3 F = mpm_material_hyper_F_of_stress(par, mpm_points_stress(pts, p));
    double *const fp[9] = {&pts->fxx[p], &pts->fxy[p], &pts->fxz[p], &pts->fyx[p], &pts->fyy[p],
                           &pts->fyz[p], &pts->fzx[p], &pts->fzy[p], &pts->fzz[p]};
    for (int k = 0; k < 9; k++)
      *fp[k] = F.m[k / 3][k % 3];
    if (!isfinite(F.m[0][0] + F.m[1][1] + F.m[2][2]))
      return mpm_err_set(err, MPM_EINPUT, "fill3: point %zu: no elastic state gives its "
                         "initial stress", p);
  }
  return MPM_OK;
}

void mpm_scenario_region3(const mpm_fill_config *f, mpm_fill3_region *r)
{
  memset(r, 0, sizeof *r);
  if (f->shape == MPM_FILL_POLYGON) {
    r->shape = MPM_FILL3_PRISM;
    r->polygon = f;
    r->lo[2] = f->zmin;
    r->hi[2] = f->zmax;
  } else if (f->shape == MPM_FILL_DISC) {
    r->shape = MPM_FILL3_CYLINDER;
    r->axis = 2;
    r->centre[0] = f->cx;
    r->centre[1] = f->cy;
    r->centre[2] = 0.5 * (f->zmin + f->zmax);
    r->radius = f->radius;
    r->length = f->zmax - f->zmin;
  } else {
    r->shape = MPM_FILL3_BOX;
    const double lo[3] = {f->xmin, f->ymin, f->zmin}, hi[3] = {f->xmax, f->ymax, f->zmax};
    memcpy(r->lo, lo, sizeof lo);
    memcpy(r->hi, hi, sizeof hi);
  }
  r->ppu = f->ppu;
  r->density = f->density;
  r->v[0] = f->vx;
  r->v[1] = f->vy;
  r->v[2] = f->vz;
}
