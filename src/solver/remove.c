/* remove.c: points leave the simulation ([DK15] sections 4.2, 4.3): below a
 * level, or out of the mesh through an open outlet (or a free edge when
 * allowed). Their mass is added to s->mass_removed, so the mass in the domain
 * plus the removed mass stays the initial mass to round-off. */
#include "solver/solver.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "diag/region.h"

/* fate of point p of a 3D run (see fate). */
static int fate3(const mpm_sim *s, size_t p)
{
  const mpm_mesh3 *m = &s->mesh3;
  const mpm_points *P = s->pts;
  const double x[3] = {P->x[p], P->y[p], P->z[p]};
  if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
    return -1;
  if (x[1] < s->cfg.remove.below)
    return 1;
  const double lo[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const int per[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  int out = 0, blocked = 0;
  for (int d = 0; d < 3; d++) {
    const int below = !per[d] && x[d] < lo[d], above = !per[d] && x[d] > lo[d] + len[d];
    out |= below | above;
    blocked |= (below && s->bc3.face[2 * d] != MPM_BC_FREE) ||
               (above && s->bc3.face[2 * d + 1] != MPM_BC_FREE);
  }
  if (!out)
    return 0;
  if (mpm_bc3_left_through_outlet(&s->bc3, m, x))
    return 1;
  return s->cfg.remove.free_edges && !blocked ? 1 : -1;
}

/* 0: stays; 1: removed; -1: outside the mesh where nothing lets it leave. */
static int fate(const mpm_sim *s, size_t p)
{
  if (s->dim == 3)
    return fate3(s, p);
  const mpm_mesh *m = &s->mesh;
  const mpm_config *c = &s->cfg;
  const double x = s->pts->x[p], y = s->pts->y[p];
  if (!isfinite(x) || !isfinite(y))
    return -1;                                   /* nowhere: said by mpm_sim_check_state */
  if (y < c->remove.below)
    return 1;
  const int out_l = !m->periodic_x && x < m->x0, out_r = !m->periodic_x && x > m->x0 + m->lx;
  const int out_b = !m->periodic_y && y < m->y0, out_t = !m->periodic_y && y > m->y0 + m->ly;
  if (!(out_l || out_r || out_b || out_t))
    return 0;
  if (mpm_bc_left_through_outlet(&s->bc, m, x, y))
    return 1;
  if (!c->remove.free_edges)
    return -1;
  const int *e = s->bc.edge;
  if ((out_l && e[MPM_EDGE_LEFT] != MPM_BC_FREE) || (out_r && e[MPM_EDGE_RIGHT] != MPM_BC_FREE) ||
      (out_b && e[MPM_EDGE_BOTTOM] != MPM_BC_FREE) || (out_t && e[MPM_EDGE_TOP] != MPM_BC_FREE))
    return -1;
  return 1;
}

/* Keep the entries of a per-point array of n values whose keep flag is set,
 * in order (as mpm_points_compact does for the point store). */
static void compact_values(double *a, const unsigned char *keep, size_t n)
{
  size_t q = 0;
  for (size_t p = 0; p < n; p++)
    if (keep[p])
      a[q++] = a[p];
}

/* mpm_sim_may_leave for a 3D run. */
static int may_leave3(const mpm_sim *s, size_t a, size_t b)
{
  const mpm_mesh3 *m = &s->mesh3;
  const mpm_points *P = s->pts;
  const double lo[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const int per[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  const double *const x[3] = {P->x, P->y, P->z};
  int any = 0;
  for (int d = 0; d < 3; d++) {
    double l = per[d] ? -INFINITY : lo[d];
    const double h = per[d] ? INFINITY : lo[d] + len[d];
    if (d == 1 && s->cfg.remove.below > l)
      l = s->cfg.remove.below;
    for (size_t p = a; p < b; p++)
      any |= !(x[d][p] >= l) | !(x[d][p] <= h);
  }
  return any;
}

int mpm_sim_may_leave(const mpm_sim *s, size_t a, size_t b)
{
  if (s->dim == 3)
    return may_leave3(s, a, b);
  const mpm_mesh *m = &s->mesh;
  const mpm_points *P = s->pts;
  const double xlo = m->periodic_x ? -INFINITY : m->x0;
  const double xhi = m->periodic_x ? INFINITY : m->x0 + m->lx;
  const double yhi = m->periodic_y ? INFINITY : m->y0 + m->ly;
  double ylo = m->periodic_y ? -INFINITY : m->y0;
  ylo = s->cfg.remove.below > ylo ? s->cfg.remove.below : ylo;
  const double *x = P->x, *y = P->y;
  int any = 0;
  for (size_t p = a; p < b; p++)
    any |= !(x[p] >= xlo) | !(x[p] <= xhi) | !(y[p] >= ylo) | !(y[p] <= yhi);
  return any;
}

int mpm_sim_remove_points(mpm_sim *s, double t, mpm_err *err)
{
  mpm_points *P = s->pts;
  if (!(s->scan & MPM_SIM_SCAN_LEAVE) || !mpm_sim_may_leave(s, 0, P->n))
    return MPM_OK;
  size_t first = P->n;
  for (size_t p = 0; p < P->n; p++) {
    const int f = fate(s, p);
    if (f < 0 && mpm_sim_check_state(s, t, err) != MPM_OK)
      return err ? err->code : MPM_ENONFINITE;   /* a blow-up, not a point gone astray */
    if (f < 0) {
      char z[40] = "";
      if (P->z)
        snprintf(z, sizeof z, ", %.6g", P->z[p]);
      return mpm_err_set(err, MPM_EOUTSIDE,
                         "point %d left the mesh at (%.6g, %.6g%s) m, t = %.6g s, not through "
                         "an open outlet or a removing edge", P->id[p], P->x[p], P->y[p], z, t);
    }
    if (f > 0 && first == P->n)
      first = p;
  }
  if (first == P->n)
    return MPM_OK;                               /* nothing leaves: the common case */
  unsigned char *keep = malloc(P->n);
  if (!keep)
    return mpm_err_set(err, MPM_ENOMEM, "point removal: out of memory");
  for (size_t p = 0; p < P->n; p++) {
    keep[p] = p < first || fate(s, p) == 0;
    if (!keep[p]) {
      s->mass_removed += P->mass[p];
      s->nremoved++;
    }
  }
  const size_t n = P->n;
  mpm_points_compact(P, keep);
  if (s->lxx) {                                  /* NGF's stored L_p follow their points */
    double *arrs[] = {s->lxx, s->lxy, s->lyx, s->lyy};
    for (size_t k = 0; k < 4; k++)
      compact_values(arrs[k], keep, n);
  }
  free(keep);
  return MPM_OK;
}

double mpm_sim_region_mass(const mpm_sim *s)
{
  const mpm_config *c = &s->cfg;
  return mpm_diag_region_mass(s->pts, c->region.xmin, c->region.xmax, c->region.ymin,
                              c->region.ymax);
}
