/* diag.c: whole-body diagnostics of the point set (one row per output frame).
 *
 *   kinetic  K   = sum_p m_p |v_p|^2 / 2
 *   momentum P   = sum_p m_p v_p
 *   centre   x_c = sum_p m_p x_p / sum_p m_p
 *   pressure p_m = sum_p m_p p_p / sum_p m_p,  p_p = -(sxx + syy + szz) / 3
 *
 * One loop serves both store dimensions: the z terms (vz in |v|^2, pz, the
 * z of the centre) are added only when the store has the z arrays, so a 2D
 * store's sums are those of plane strain bit for bit.
 *
 * Sums run serially in point order and accumulate in double, so a row does
 * not depend on the thread count of the run that produced the points. */
#include "diag/diag.h"

#include <stdio.h>
#include <string.h>

#include "core/error.h"

/* Running sums over the points, in point order. */
typedef struct diag_sums {
  double m, vol, ke, px, py, pz, mx, my, mz, mp;
  size_t ndisc;
} diag_sums;

/* The z arrays of a 3D store; NULL for a 2D store, whose arrays are NULL
 * anyway (checked on dim so that a 2D store's pointers are never read). */
static const double *diag_z(const mpm_points *pts, const double *a)
{
  return mpm_points_has(pts, 3) ? a : NULL;
}

/* |v|^2 of point i: vz^2 added only for a 3D store (vz non-NULL), so the
 * 2D value is vx^2 + vy^2 exactly. */
static inline double diag_v2(const mpm_points *pts, const double *vz, size_t i)
{
  double vx = pts->vx[i], vy = pts->vy[i];
  double v2 = vx * vx + vy * vy;
  if (vz)
    v2 += vz[i] * vz[i];
  return v2;
}

static void diag_accumulate(const mpm_points *pts, diag_sums *s)
{
  const double *z = diag_z(pts, pts->z), *vz = diag_z(pts, pts->vz);
  memset(s, 0, sizeof *s);
  for (size_t i = 0; i < pts->n; i++) {
    double m = pts->mass[i];
    double p = mpm_points_pressure(pts, i);
    s->m += m;
    s->vol += pts->vol[i];
    s->ke += 0.5 * m * diag_v2(pts, vz, i);    /* m |v|^2 / 2 */
    s->px += m * pts->vx[i];
    s->py += m * pts->vy[i];
    s->mx += m * pts->x[i];
    s->my += m * pts->y[i];
    if (z) {
      s->pz += m * vz[i];
      s->mz += m * z[i];
    }
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
  d->pz = s.pz;
  d->mass = s.m;
  d->volume = s.vol;
  d->npoints = pts->n;
  d->ndisconnected = s.ndisc;
  if (s.m > 0.0) {
    d->kinetic_per_mass = s.ke / s.m;
    d->xcm = s.mx / s.m;
    d->ycm = s.my / s.m;
    d->zcm = s.mz / s.m;
    d->pmean = s.mp / s.m;
  }
}

double mpm_diag_kinetic_per_mass(const mpm_points *pts)
{
  const double *vz = diag_z(pts, pts->vz);
  double m = 0.0, ke = 0.0;
  for (size_t i = 0; i < pts->n; i++) {
    m += pts->mass[i];
    ke += 0.5 * pts->mass[i] * diag_v2(pts, vz, i);
  }
  return m > 0.0 ? ke / m : 0.0;
}

/* The 2D columns, in every store dimension; a 3D file appends pz and zcm
 * so that a column keeps its position (scripts read them by number). */
#define DIAG_HEAD_2D "t,kinetic,kinetic_per_mass,px,py,mass,volume,xcm,ycm,pmean," \
                     "npoints,ndisconnected,stop,mass_removed,nremoved,mass_region"

const char *mpm_diag_csv_header(int dim)
{
  return dim == 3 ? DIAG_HEAD_2D ",pz,zcm\n" : DIAG_HEAD_2D "\n";
}

int mpm_diag_csv_row(const mpm_diag *d, int dim, char *buf, size_t len)
{
  if (!d || !buf || len == 0)
    return MPM_EINVAL;
  int w = snprintf(buf, len,
                   "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,"
                   "%zu,%zu,%d,%.10g,%ld,%.10g",
                   d->t, d->kinetic, d->kinetic_per_mass, d->px, d->py, d->mass,
                   d->volume, d->xcm, d->ycm, d->pmean, d->npoints, d->ndisconnected, d->stop,
                   d->mass_removed, d->nremoved, d->mass_region);
  if (w >= 0 && (size_t)w < len) {
    int w2 = dim == 3 ? snprintf(buf + w, len - (size_t)w, ",%.10g,%.10g\n", d->pz, d->zcm)
                      : snprintf(buf + w, len - (size_t)w, "\n");
    w = w2 < 0 ? -1 : w + w2;
  }
  if (w < 0 || (size_t)w >= len) {
    buf[0] = '\0';
    return MPM_EINVAL;
  }
  return MPM_OK;
}
