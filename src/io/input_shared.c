/* input_shared.c: what the checks of the input share (input_check.c and
 * the checks of the titled sections' items, input_fill.c and input_body.c):
 * whether a key was set and which of two related keys to name, the mesh
 * along an axis, the keys of an item's form (its shape), and a polygon's
 * vertices. It calls none of the checks. */
#include <math.h>

#include "io/input_internal.h"

/* 1 if key was set (in the file or with --set) in item `item` (-1: a plain
 * section). */
int mpm_io_in_is_set(const in_ctx *c, int key, int item)
{
  const loc *l = &c->at[item < 0 ? 0 : item][key];
  return l->line > 0 || l->ovr > 0;
}

/* 1 if a was set after b (a --set counts after the file). */
static int later(loc a, loc b)
{
  if (a.ovr != b.ovr)
    return a.ovr > b.ovr;
  return a.line > b.line;
}

/* Where to report a relation between keys a and b: the one set last. */
where mpm_io_in_blame(const in_ctx *c, const mpm_config *cfg, int item, int a, int b)
{
  const loc *la = &c->at[item < 0 ? 0 : item][a], *lb = &c->at[item < 0 ? 0 : item][b];
  int k = later(*lb, *la) ? b : a;
  const int t = mpm_io_in_titled_of(mpm_io_in_keys[k].sec);
  where w = {.at = k == a ? *la : *lb,
             .sec = mpm_io_in_keys[k].sec,
             .key = k,
             .item = item,
             .title = item >= 0 && t >= 0 ? mpm_io_in_title(cfg, t, item) : NULL};
  return w;
}

/* The mesh along axis a (0 x, 1 y, 2 z). */
mesh_axis mpm_io_in_mesh_axis(const mpm_config *cfg, int a)
{
  const double d[3] = {cfg->mesh.dx, cfg->mesh.dy, cfg->mesh.dz};
  const double o[3] = {cfg->mesh.x0, cfg->mesh.y0, cfg->mesh.z0};
  const int n[3] = {cfg->mesh.nx, cfg->mesh.ny, cfg->mesh.nz};
  return (mesh_axis){o[a], d[a], n[a]};
}

/* The form of item i of titled section t as messages name it: its shape,
 * and for a fill cylinder its axis ("disc" with axis "x"). */
static text form_name(const mpm_config *cfg, int t, int i)
{
  text s = {{0}};
  const void *rec = mpm_io_in_item_of(cfg, t, i);
  const key_def *ks = &mpm_io_in_keys[mpm_io_in_find_key(mpm_io_in_titled[t].sec, "shape")];
  const int shape = *(const int *)(const void *)((const char *)rec + ks->off);
  mpm_io_in_addf(&s, "\"%s\"", mpm_io_in_name_at(ks->kind, shape));
  if (t == T_FILL && (mpm_io_in_fill_form(rec, cfg->mesh.nz > 0) & SH_CYL))
    mpm_io_in_addf(&s, " with axis \"%s\"",
                   mpm_io_in_name_at(NK_FILL_AXIS, ((const mpm_fill_config *)rec)->axis));
  return s;
}

/* The axis (0 x, 1 y, 2 z) that fill key k spans (xmin ... zmax), or -1. */
static int span_axis(int k)
{
  const char *const span[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (int a = 0; a < 3; a++)
    if (k == mpm_io_in_find_key(S_FILL, span[a][0]) ||
        k == mpm_io_in_find_key(S_FILL, span[a][1]))
      return a;
  return -1;
}

/* Item i of titled section t: the keys of another form (a plane shape; for
 * a 3D fill also a box, a prism or a cylinder along another axis) must not
 * be set; the form's own required keys must, and those of every form. A
 * fill cylinder's missing span key names the mesh along its axis. */
int mpm_io_in_check_form_keys(in_ctx *c, const mpm_config *cfg, int t, int i)
{
  const int sec = mpm_io_in_titled[t].sec;
  const int form = mpm_io_in_item_form(t, mpm_io_in_item_of(cfg, t, i), cfg->mesh.nz > 0);
  const text name = form_name(cfg, t, i);
  for (int k = 0; k < NKEYS; k++) {
    const key_def *kd = &mpm_io_in_keys[k];
    if (kd->sec != sec || !(kd->shapes || (kd->flags & KF_REQUIRED)))
      continue;
    where w = {.at = c->at[i][k], .sec = sec, .key = k, .item = i,
               .title = mpm_io_in_title(cfg, t, i)};
    if (!kd->shapes) {
      if (mpm_io_in_is_set(c, k, i))
        continue;
      return mpm_io_in_fail_key(c, &w, "required, not set (allowed: %s)",
                                mpm_io_in_allowed_text(kd).s);
    }
    if (!(kd->shapes & form) && mpm_io_in_is_set(c, k, i))
      return mpm_io_in_fail_key(c, &w, "not used by shape %s (allowed keys for %s: %s)", name.s,
                                name.s, mpm_io_in_key_list(sec, form).s);
    if (!(kd->shapes & form) || !(kd->flags & KF_REQUIRED) || mpm_io_in_is_set(c, k, i))
      continue;
    const int a = span_axis(k);
    if (t == T_FILL && (form & SH_CYL) && a >= 0) {
      const mesh_axis ax = mpm_io_in_mesh_axis(cfg, a);
      return mpm_io_in_fail_key(c, &w, "required for shape %s, not set (allowed: %s ... %s m)",
                                name.s, mpm_io_in_approx(ax.o).s,
                                mpm_io_in_approx(ax.o + ax.n * ax.d).s);
    }
    return mpm_io_in_fail_key(c, &w, "required for shape %s, not set (allowed: %s)", name.s,
                              mpm_io_in_allowed_text(kd).s);
  }
  return MPM_OK;
}

static void bounds(const double *v, int n, double *lo, double *hi)
{
  *lo = *hi = v[0];
  for (int j = 1; j < n; j++) {
    *lo = v[j] < *lo ? v[j] : *lo;
    *hi = v[j] > *hi ? v[j] : *hi;
  }
}

/* The polygon of item i (list keys kx, ky of its section; values px, py):
 * as many x as y values, 3 ... MPM_MAX_POLY of them around a region. Its
 * bounding box in box (xmin, xmax, ymin, ymax). */
int mpm_io_in_check_vertices(in_ctx *c, const mpm_config *cfg, int i, int kx, int ky,
                             const double *px, const double *py, double box[4])
{
  const int nx = c->nlist[i][kx], ny = c->nlist[i][ky];
  where w = mpm_io_in_blame(c, cfg, i, ky, kx);
  if (nx != ny)
    return mpm_io_in_fail_key(
        c, &w, "x has %d values, y has %d (allowed: as many x values as y values)", nx, ny);
  if (nx < 3)
    return mpm_io_in_fail_key(c, &w, "%d vertices (allowed: 3 ... %d vertices)", nx, MPM_MAX_POLY);
  double area = 0;
  for (int a = 0, b = nx - 1; a < nx; b = a++)
    area += px[b] * py[a] - px[a] * py[b];  /* 2A = sum x_b y_a - x_a y_b */
  bounds(px, nx, &box[0], &box[1]);
  bounds(py, nx, &box[2], &box[3]);
  if (!(fabs(area) > 1e-12 * (box[1] - box[0]) * (box[3] - box[2])))
    return mpm_io_in_fail_key(
        c, &w, "the polygon encloses no area (allowed: 3 ... %d vertices around a region)",
        MPM_MAX_POLY);
  return MPM_OK;
}
