/* input_fill.c: the checks of a fill that no single range can state: the
 * keys of its form (its shape, and in 3D a cylinder's axis), its region
 * inside the mesh (a rectangle, a disc or cylinder, a polygon), the density
 * that defaults to material.rho_c, and its initial stress. Its z range in 3D
 * is checked with the other 3D keys (input_check.c). */
#include <math.h>

#include "io/input_internal.h"

static int fill_key(const char *name)
{
  return mpm_io_in_find_key(S_FILL, name);  /* the table is fixed: names used here exist */
}

/* The fill's extent lo ... hi along axis a (0 x, 1 y, 2 z), from keys ka
 * and kb, inside the mesh. */
static int check_span(in_ctx *c, const mpm_config *cfg, int i, int ka, int kb, double lo,
                      double hi, int a)
{
  const mesh_axis ax = mpm_io_in_mesh_axis(cfg, a);
  const double m0 = ax.o, m1 = m0 + ax.n * ax.d, tol = GEOM_TOL * ax.d;
  if (lo >= m0 - tol && hi <= m1 + tol)
    return MPM_OK;
  where w = mpm_io_in_blame(c, cfg, i, ka, kb);
  return mpm_io_in_fail_key(c, &w,
                            "the fill spans %c %s ... %s, outside the mesh (allowed: %s ... %s m)",
                            "xyz"[a], mpm_io_in_approx(lo).s, mpm_io_in_approx(hi).s,
                            mpm_io_in_approx(m0).s, mpm_io_in_approx(m1).s);
}

/* xmin < xmax (a = 0) or ymin < ymax (a = 1). */
static int check_order(in_ctx *c, const mpm_config *cfg, int i, int a)
{
  const mpm_fill_config *f = &cfg->fill[i];
  const char *lo_key = a ? "ymin" : "xmin", *hi_key = a ? "ymax" : "xmax";
  const double lo = a ? f->ymin : f->xmin, hi = a ? f->ymax : f->xmax;
  if (lo < hi)
    return MPM_OK;
  where w = mpm_io_in_blame(c, cfg, i, fill_key(hi_key), fill_key(lo_key));
  return mpm_io_in_fail_key(c, &w, "%s = %s >= %s = %s (allowed: %s < %s)", lo_key,
                            mpm_io_in_num(lo).s, hi_key, mpm_io_in_num(hi).s, lo_key, hi_key);
}

static int check_rectangle(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_fill_config *f = &cfg->fill[i];
  int kx0 = fill_key("xmin"), kx1 = fill_key("xmax");
  int ky0 = fill_key("ymin"), ky1 = fill_key("ymax");
  if (check_order(c, cfg, i, 0) != MPM_OK || check_order(c, cfg, i, 1) != MPM_OK)
    return MPM_EINPUT;
  if (check_span(c, cfg, i, kx1, kx0, f->xmin, f->xmax, 0) != MPM_OK)
    return MPM_EINPUT;
  return check_span(c, cfg, i, ky1, ky0, f->ymin, f->ymax, 1);
}

/* A disc: its circle inside the mesh, across its axis (z in the plane; in
 * 3D fill.axis). A cylinder along x or y also spans xmin < xmax or ymin <
 * ymax inside the mesh; the z range of one along z is every 3D fill's
 * (check_dimension). */
static int check_disc(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_fill_config *f = &cfg->fill[i];
  const int a = cfg->mesh.nz > 0 ? f->axis : 2;
  const int kr = fill_key("radius");
  const int kc[3] = {fill_key("cx"), fill_key("cy"), fill_key("cz")};
  const double centre[3] = {f->cx, f->cy, f->cz};
  for (int d = 0; d < 3; d++)
    if (d != a && check_span(c, cfg, i, kc[d], kr, centre[d] - f->radius,
                             centre[d] + f->radius, d) != MPM_OK)
      return MPM_EINPUT;
  if (a == 2)
    return MPM_OK;
  if (check_order(c, cfg, i, a) != MPM_OK)
    return MPM_EINPUT;
  const int klo = fill_key(a ? "ymin" : "xmin");
  const int khi = fill_key(a ? "ymax" : "xmax");
  return check_span(c, cfg, i, khi, klo, a ? f->ymin : f->xmin, a ? f->ymax : f->xmax, a);
}

static int check_polygon(in_ctx *c, mpm_config *cfg, int i)
{
  mpm_fill_config *f = &cfg->fill[i];
  const int kx = fill_key("x"), ky = fill_key("y");
  double box[4];
  if (mpm_io_in_check_vertices(c, cfg, i, kx, ky, f->px, f->py, box) != MPM_OK)
    return MPM_EINPUT;
  f->nvert = c->nlist[i][kx];
  if (check_span(c, cfg, i, kx, ky, box[0], box[1], 0) != MPM_OK)
    return MPM_EINPUT;
  return check_span(c, cfg, i, ky, kx, box[2], box[3], 1);
}

/* Fill i: the keys of its form, its region inside the mesh, its density and
 * initial stress. */
int mpm_io_in_check_fill(in_ctx *c, mpm_config *cfg, int i)
{
  mpm_fill_config *f = &cfg->fill[i];
  int rc = mpm_io_in_check_form_keys(c, cfg, T_FILL, i);
  if (rc == MPM_OK && f->shape == MPM_FILL_RECTANGLE)
    rc = check_rectangle(c, cfg, i);
  else if (rc == MPM_OK && f->shape == MPM_FILL_DISC)
    rc = check_disc(c, cfg, i);
  else if (rc == MPM_OK)
    rc = check_polygon(c, cfg, i);
  if (rc != MPM_OK)
    return rc;
  for (int k = 0; k < NKEYS; k++)  /* defaults taken from the material */
    if ((mpm_io_in_keys[k].flags & KF_RHO_C) && !mpm_io_in_is_set(c, k, i))
      *(double *)(void *)((char *)f + mpm_io_in_keys[k].off) = cfg->material.rho_c;
  int kd = fill_key("density");
  if (mpm_io_in_is_set(c, kd, i) && f->density > cfg->material.rho_s) {
    where w = {.at = c->at[i][kd], .sec = S_FILL, .key = kd, .item = i, .title = f->name};
    return mpm_io_in_fail_key(c, &w,
                              "density = %s > material.rho_s = %s (allowed: density <= rho_s)",
                              mpm_io_in_num(f->density).s, mpm_io_in_num(cfg->material.rho_s).s);
  }
  /* The pre-stress is the weight under the full gravity, which a ramp only
   * reaches at t_ramp: at t = 0 nothing would hold it, and the fill would
   * spring apart into tension and disconnect. */
  int kl = fill_key("lithostatic");
  if (f->lithostatic && cfg->gravity.t_ramp > 0.0) {
    where w = {.at = c->at[i][kl], .sec = S_FILL, .key = kl, .item = i, .title = f->name};
    return mpm_io_in_fail_key(c, &w,
                              "lithostatic = true with gravity.t_ramp = %s s: the pre-stress "
                              "needs the full gravity from t = 0 (allowed: gravity.t_ramp = 0, or "
                              "lithostatic = false)",
                              mpm_io_in_num(cfg->gravity.t_ramp).s);
  }
  int kk = fill_key("k0");
  if (!f->lithostatic && f->k0 > 0.0) {
    where w = {.at = c->at[i][kk], .sec = S_FILL, .key = kk, .item = i, .title = f->name};
    return mpm_io_in_fail_key(c, &w,
                              "k0 = %s without lithostatic = true: the lateral stress ratio "
                              "belongs to the lithostatic pre-stress (allowed: lithostatic = "
                              "true, or no k0)",
                              mpm_io_in_num(f->k0).s);
  }
  int kp = fill_key("pressure");
  if (f->lithostatic && f->pressure > 0.0) {
    where w = mpm_io_in_blame(c, cfg, i, kp, kl);
    return mpm_io_in_fail_key(c, &w,
                              "lithostatic = true with pressure = %s Pa: two initial stresses "
                              "(allowed: one of them)",
                              mpm_io_in_num(f->pressure).s);
  }
  return MPM_OK;
}
