/* diag.c: whole-body diagnostics of the point set (one row per output frame).
 *
 *   kinetic  K   = sum_p m_p |v_p|^2 / 2
 *   momentum P   = sum_p m_p v_p
 *   centre   x_c = sum_p m_p x_p / sum_p m_p
 *   pressure p_m = sum_p m_p p_p / sum_p m_p,  p_p = -(sxx + syy + szz) / 3
 *
 * Sums run serially in point order and accumulate in double, so a row does
 * not depend on the thread count of the run that produced the points. */
#include "diag/diag.h"

#include <stdio.h>
#include <string.h>

#include "core/error.h"

/* Running sums over the points, in point order. */
typedef struct diag_sums {
  double m, vol, ke, px, py, mx, my, mp;
  size_t ndisc;
} diag_sums;

static void diag_accumulate(const mpm_points *pts, diag_sums *s)
{
  memset(s, 0, sizeof *s);
  for (size_t i = 0; i < pts->n; i++) {
    double m = pts->mass[i];
    double vx = pts->vx[i], vy = pts->vy[i];
    double p = mpm_points_pressure(pts, i);
    s->m += m;
    s->vol += pts->vol[i];
    s->ke += 0.5 * m * (vx * vx + vy * vy);    /* m |v|^2 / 2 */
    s->px += m * vx;
    s->py += m * vy;
    s->mx += m * pts->x[i];
    s->my += m * pts->y[i];
    s->mp += m * p;
    if (pts->state[i] == MPM_STATE_DISCONNECTED)
      s->ndisc++;
  }
}

/* Mass-weighted means are zero for an empty (massless) set. */
void mpm_diag_compute(const mpm_points *pts, double t, mpm_diag *d)
{
  diag_sums s;
  memset(d, 0, sizeof *d);
  d->t = t;
  if (!pts)
    return;
  diag_accumulate(pts, &s);
  d->kinetic = s.ke;
  d->px = s.px;
  d->py = s.py;
  d->mass = s.m;
  d->volume = s.vol;
  d->npoints = pts->n;
  d->ndisconnected = s.ndisc;
  if (s.m > 0.0) {
    d->kinetic_per_mass = s.ke / s.m;
    d->xcm = s.mx / s.m;
    d->ycm = s.my / s.m;
    d->pmean = s.mp / s.m;
  }
}

double mpm_diag_kinetic_per_mass(const mpm_points *pts)
{
  double m = 0.0, ke = 0.0;
  for (size_t i = 0; i < pts->n; i++) {
    double vx = pts->vx[i], vy = pts->vy[i];
    m += pts->mass[i];
    ke += 0.5 * pts->mass[i] * (vx * vx + vy * vy);
  }
  return m > 0.0 ? ke / m : 0.0;
}

const char *mpm_diag_csv_header(void)
{
  return "t,kinetic,kinetic_per_mass,px,py,mass,volume,xcm,ycm,pmean,"
         "npoints,ndisconnected,stop,mass_removed,nremoved,mass_region\n";
}

int mpm_diag_csv_row(const mpm_diag *d, char *buf, size_t len)
{
  if (!d || !buf || len == 0)
    return MPM_EINVAL;
  int w = snprintf(buf, len,
                   "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,"
                   "%zu,%zu,%d,%.10g,%ld,%.10g\n",
                   d->t, d->kinetic, d->kinetic_per_mass, d->px, d->py, d->mass,
                   d->volume, d->xcm, d->ycm, d->pmean, d->npoints, d->ndisconnected, d->stop,
                   d->mass_removed, d->nremoved, d->mass_region);
  if (w < 0 || (size_t)w >= len) {
    buf[0] = '\0';
    return MPM_EINVAL;
  }
  return MPM_OK;
}
