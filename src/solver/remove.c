/* remove.c: points leave the simulation ([DK15] sections 4.2, 4.3): below a
 * level, or out of the mesh through an open outlet (or a free edge when
 * allowed). Their mass is added to s->mass_removed, so the mass in the domain
 * plus the removed mass stays the initial mass to round-off. */
#include "solver/solver.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "diag/region.h"

/* 0: stays; 1: removed; -1: outside the mesh where nothing lets it leave. */
static int fate(const mpm_sim *s, size_t p)
{
  const mpm_mesh *m = &s->mesh;
  const mpm_points *P = s->pts;
  const double x[3] = {P->x[p], P->y[p], s->dim == 3 ? P->z[p] : 0.0};
  if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
    return -1;                                   /* nowhere: said by mpm_sim_check_state */
  if (x[1] < s->cfg.remove.below)
    return 1;
  int out = 0, blocked = 0;
  for (int d = 0; d < m->dim; d++) {
    const int per = m->periodic[d];
    const int below = !per && x[d] < m->o[d], above = !per && x[d] > m->o[d] + m->len[d];
    out |= below | above;
    blocked |= (below && s->bc.face[2 * d] != MPM_BC_FREE) ||
               (above && s->bc.face[2 * d + 1] != MPM_BC_FREE);
  }
  if (!out)
    return 0;
  if (mpm_bc_left_through_outlet(&s->bc, m, x))
    return 1;
  return s->cfg.remove.free_edges && !blocked ? 1 : -1;
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

/* The box a point stays in, lo[d] <= x_d <= hi[d] on every axis: the mesh
 * (no bound along a periodic axis), above the removal level. A point inside
 * it stays (fate 0); only one outside it needs fate(). */
static void staying_box(const mpm_sim *s, double lo[3], double hi[3])
{
  const mpm_mesh *m = &s->mesh;
  for (int d = 0; d < 3; d++) {
    lo[d] = d >= m->dim || m->periodic[d] ? -INFINITY : m->o[d];
    hi[d] = d >= m->dim || m->periodic[d] ? INFINITY : m->o[d] + m->len[d];
  }
  lo[1] = s->cfg.remove.below > lo[1] ? s->cfg.remove.below : lo[1];
}

static inline int in_box(const mpm_points *P, int D, const double lo[3], const double hi[3],
                         size_t p)
{
  return P->x[p] >= lo[0] && P->x[p] <= hi[0] && P->y[p] >= lo[1] && P->y[p] <= hi[1] &&
         (D == 2 || (P->z[p] >= lo[2] && P->z[p] <= hi[2]));
}

/* mpm_sim_may_leave over D axes (a constant where it is inlined): one pass
 * that vectorises. */
static inline int may_leave_dim(const mpm_sim *s, int D, size_t a, size_t b)
{
  const mpm_points *P = s->pts;
  double lo[3], hi[3];
  staying_box(s, lo, hi);
  const double *const x = P->x, *const y = P->y, *const z = P->z;
  int any = 0;
  if (D == 3)
    for (size_t p = a; p < b; p++)
      any |= !(x[p] >= lo[0]) | !(x[p] <= hi[0]) | !(y[p] >= lo[1]) | !(y[p] <= hi[1]) |
             !(z[p] >= lo[2]) | !(z[p] <= hi[2]);
  else
    for (size_t p = a; p < b; p++)
      any |= !(x[p] >= lo[0]) | !(x[p] <= hi[0]) | !(y[p] >= lo[1]) | !(y[p] <= hi[1]);
  return any;
}

int mpm_sim_may_leave(const mpm_sim *s, size_t a, size_t b)
{
  return s->dim == 3 ? may_leave_dim(s, 3, a, b) : may_leave_dim(s, 2, a, b);
}

int mpm_sim_remove_points(mpm_sim *s, double t, mpm_err *err)
{
  mpm_points *P = s->pts;
  if (!(s->scan & MPM_SIM_SCAN_LEAVE) || !mpm_sim_may_leave(s, 0, P->n))
    return MPM_OK;
  double lo[3], hi[3];
  staying_box(s, lo, hi);
  const int D = s->dim;
  size_t first = P->n;
  for (size_t p = 0; p < P->n; p++) {
    if (in_box(P, D, lo, hi, p))
      continue;                                  /* stays: most points */
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
    keep[p] = p < first || in_box(P, D, lo, hi, p) || fate(s, p) == 0;
    if (!keep[p]) {
      s->mass_removed += P->mass[p];
      s->nremoved++;
    }
  }
  const size_t n = P->n;
  mpm_points_compact(P, keep);
  for (int k = 0; k < s->dim * s->dim && s->L[k]; k++)  /* the stored L_p follow their points */
    compact_values(s->L[k], keep, n);
  free(keep);
  return MPM_OK;
}

double mpm_sim_region_mass(const mpm_sim *s)
{
  const mpm_config *c = &s->cfg;
  return mpm_diag_region_mass(s->pts, c->region.xmin, c->region.xmax, c->region.ymin,
                              c->region.ymax);
}
