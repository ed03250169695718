/* body.c: the geometry, contact rule and motion of a rigid body (body.h;
 * docs/model.md, "Rigid bodies and contact").
 *
 * Geometry: in the body's frame, (u, w) = R(-theta) (x_e0 - c_e0, x_e1 - c_e1)
 * and s = x_e2 - c_e2 along the axis, the profile's signed distance d(u, w)
 * (negative inside) is extruded over |s| <= length/2 as the exact distance
 * to the prism: max(d, |s| - L/2) inside, the length of the positive parts
 * outside. phi = d for material outside the body, -d for material inside.
 * Motion: a prescribed degree of freedom moves by dt times its table at the
 * middle of the step (exact for a table linear over the step); a free one
 * is integrated by symplectic Euler, v += dt F/m, then x += dt v. */
#include "bc/body.h"

#include <math.h>

#include "core/names.h"

static const char *const shape_names[] = {
  [MPM_BODY_DISC] = "disc", [MPM_BODY_BOX] = "box", [MPM_BODY_POLYGON] = "polygon"};
static const char *const side_names[] = {[MPM_BODY_OUTSIDE] = "outside",
                                         [MPM_BODY_INSIDE] = "inside"};
static const char *const contact_names[] = {[MPM_CONTACT_NOSLIP] = "noslip",
                                            [MPM_CONTACT_FRICTIONLESS] = "frictionless",
                                            [MPM_CONTACT_FRICTION] = "friction"};

#define NAME_AT(table, i) mpm_names_at(table, MPM_NAMES_COUNT(table), i)
#define NAME_INDEX(table, s) mpm_names_index(table, MPM_NAMES_COUNT(table), s)

const char *mpm_body_shape_name(int shape) { return NAME_AT(shape_names, shape); }
int mpm_body_shape_from_name(const char *name) { return NAME_INDEX(shape_names, name); }
const char *mpm_body_side_name(int side) { return NAME_AT(side_names, side); }
int mpm_body_side_from_name(const char *name) { return NAME_INDEX(side_names, name); }
const char *mpm_body_contact_name(int contact) { return NAME_AT(contact_names, contact); }
int mpm_body_contact_from_name(const char *name) { return NAME_INDEX(contact_names, name); }

static double profile_reach(const mpm_body_config *cfg);

void mpm_body_init(mpm_body *b, const mpm_body_config *cfg, int dim)
{
  *b = (mpm_body){.cfg = cfg, .dim = dim};
  const int axis = dim == 3 ? cfg->axis : 2;
  b->e[0] = (axis + 1) % 3;                  /* cyclic: (x, y, z), (y, z, x), (z, x, y) */
  b->e[1] = (axis + 2) % 3;
  b->e[2] = axis;
  b->s.c[0] = cfg->cx;
  b->s.c[1] = cfg->cy;
  b->s.c[2] = dim == 3 ? cfg->cz : 0.0;
  mpm_body_turned(b, cfg->angle * (3.14159265358979323846 / 180.0));
  for (int k = 0; k < MPM_BODY_NDOF; k++)
    b->s.v[k] = mpm_body_table(cfg, k, 0.0);
  const double r = profile_reach(cfg);
  b->reach2 = r * r;
  if (dim == 2)
    b->s.v[MPM_BODY_VZ] = 0.0;
}

double mpm_body_table(const mpm_body_config *cfg, int k, double t)
{
  const int n = cfg->nval[k];
  const double *v = cfg->val[k], *T = cfg->t;
  if (n <= 1)
    return n == 1 ? v[0] : 0.0;
  if (t <= T[0])
    return v[0];
  if (t >= T[n - 1])
    return v[n - 1];
  int i = 0;
  while (i + 2 < n && t >= T[i + 1])
    i++;
  const double s = (t - T[i]) / (T[i + 1] - T[i]);
  return v[i] + s * (v[i + 1] - v[i]);
}

/* ---- geometry ------------------------------------------------------------ */

/* Distance from (u, w) to the segment a-b and the nearest point on it. */
static double segment_distance(double u, double w, double ax, double ay, double bx, double by,
                               double *qx, double *qy)
{
  const double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
  double s = l2 > 0.0 ? ((u - ax) * ex + (w - ay) * ey) / l2 : 0.0;
  s = s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
  *qx = ax + s * ex;
  *qy = ay + s * ey;
  return sqrt((u - *qx) * (u - *qx) + (w - *qy) * (w - *qy));
}

/* The profile's signed distance at (u, w), negative inside, and its unit
 * gradient g. */
static double profile_distance(const mpm_body_config *cfg, double u, double w, double g[2])
{
  switch (cfg->shape) {
  case MPM_BODY_DISC: {
    const double r = sqrt(u * u + w * w);
    g[0] = r > 0.0 ? u / r : 1.0;
    g[1] = r > 0.0 ? w / r : 0.0;
    return r - cfg->radius;
  }
  case MPM_BODY_BOX: {
    const double qx = fabs(u) - cfg->hx, qy = fabs(w) - cfg->hy;
    const double su = u < 0.0 ? -1.0 : 1.0, sw = w < 0.0 ? -1.0 : 1.0;
    if (qx <= 0.0 && qy <= 0.0) {           /* inside: the nearer side */
      g[0] = qx >= qy ? su : 0.0;
      g[1] = qx >= qy ? 0.0 : sw;
      return fmax(qx, qy);
    }
    const double ox = fmax(qx, 0.0), oy = fmax(qy, 0.0), d = hypot(ox, oy);
    g[0] = su * ox / d;
    g[1] = sw * oy / d;
    return d;
  }
  default: {                                 /* polygon: nearest side, crossing parity */
    const int n = cfg->nvert;
    double best = INFINITY, bx = 0.0, by = 0.0;
    int in = 0;
    for (int i = 0, j = n - 1; i < n; j = i++) {
      const double xi = cfg->px[i], yi = cfg->py[i], xj = cfg->px[j], yj = cfg->py[j];
      double qx, qy;
      const double dd = segment_distance(u, w, xj, yj, xi, yi, &qx, &qy);
      if (dd < best) {
        best = dd;
        bx = qx;
        by = qy;
      }
      if ((yi > w) != (yj > w) && u < xj + (w - yj) * (xi - xj) / (yi - yj))
        in = !in;
    }
    const double s = in ? -1.0 : 1.0;        /* grad: away from the nearest point outside */
    g[0] = best > 0.0 ? s * (u - bx) / best : 1.0;
    g[1] = best > 0.0 ? s * (w - by) / best : 0.0;
    return s * best;
  }
  }
}

double mpm_body_phi(const mpm_body *b, const double x[3], double n[3])
{
  const mpm_body_config *cfg = b->cfg;
  const double ct = b->ct, st = b->sn;
  const double X = x[b->e[0]] - b->s.c[b->e[0]], Y = x[b->e[1]] - b->s.c[b->e[1]];
  const double u = ct * X + st * Y, w = -st * X + ct * Y;   /* R(-theta) (X, Y) */
  double g[2];
  double d = profile_distance(cfg, u, w, g);
  double ga = 0.0;                           /* the gradient's part along the axis */
  if (b->dim == 3 && cfg->length > 0.0) {    /* the prism's ends */
    const double s = x[b->e[2]] - b->s.c[b->e[2]];
    const double a = fabs(s) - 0.5 * cfg->length, sa = s < 0.0 ? -1.0 : 1.0;
    if (d <= 0.0 && a <= 0.0) {
      if (a > d) {
        d = a;
        g[0] = g[1] = 0.0;
        ga = sa;
      }
    } else {
      const double pd = fmax(d, 0.0), pa = fmax(a, 0.0), r = hypot(pd, pa);
      g[0] *= pd / r;
      g[1] *= pd / r;
      ga = sa * pa / r;
      d = r;
    }
  }
  const double sgn = cfg->side == MPM_BODY_INSIDE ? -1.0 : 1.0;
  if (n) {
    n[b->e[0]] = sgn * (ct * g[0] - st * g[1]);              /* R(theta) g */
    n[b->e[1]] = sgn * (st * g[0] + ct * g[1]);
    n[b->e[2]] = sgn * ga;
  }
  return sgn * d;
}

void mpm_body_velocity_at(const mpm_body *b, const double x[3], double vb[3])
{
  const double om = b->s.v[MPM_BODY_OMEGA];
  const int e0 = b->e[0], e1 = b->e[1];
  for (int d = 0; d < 3; d++)
    vb[d] = b->s.v[d];
  vb[e0] -= om * (x[e1] - b->s.c[e1]);         /* omega a x r, a = e2 */
  vb[e1] += om * (x[e0] - b->s.c[e0]);
  if (b->dim == 2)
    vb[2] = 0.0;
}

int mpm_body_contact(const mpm_body_config *cfg, int D, const double vb[3], const double n[3],
                     double v[3])
{
  double w[3] = {0.0, 0.0, 0.0}, wn = 0.0;
  for (int d = 0; d < D; d++) {
    w[d] = v[d] - vb[d];
    wn += w[d] * n[d];
  }
  if (!(wn < 0.0))
    return 0;                                /* separating, or at rest against it */
  double keep = 0.0;                         /* the share of the tangential part kept */
  if (cfg->contact != MPM_CONTACT_NOSLIP) {
    double t2 = 0.0;
    for (int d = 0; d < D; d++) {
      w[d] -= wn * n[d];
      t2 += w[d] * w[d];
    }
    keep = 1.0;
    if (cfg->contact == MPM_CONTACT_FRICTION) {
      const double wt = sqrt(t2), slip = wt + cfg->friction * wn;  /* |w_t| - mu |w_n| */
      keep = slip > 0.0 ? slip / wt : 0.0;
    }
  }
  for (int d = 0; d < D; d++)
    v[d] = vb[d] + keep * w[d];
  return 1;
}

/* ---- motion -------------------------------------------------------------- */

void mpm_body_prescribe(mpm_body *b, double t, double dt)
{
  for (int k = 0; k < MPM_BODY_NDOF; k++)
    if (!b->cfg->free[k] && (b->dim == 3 || k != MPM_BODY_VZ))
      b->s.v[k] = mpm_body_table(b->cfg, k, t + 0.5 * dt);
}

double mpm_body_axial_torque(const mpm_body *b)
{
  return b->s.tq[b->e[2]];
}

void mpm_body_advance(mpm_body *b, double dt, const double g[3])
{
  const mpm_body_config *cfg = b->cfg;
  for (int d = 0; d < b->dim; d++)
    if (cfg->free[d])
      b->s.v[d] += dt * ((b->s.f[d] + cfg->force[d]) / cfg->mass + g[d] - cfg->damping * b->s.v[d]);
  if (cfg->free[MPM_BODY_OMEGA])
    b->s.v[MPM_BODY_OMEGA] += dt * ((mpm_body_axial_torque(b) + cfg->torque) / cfg->inertia -
                                  cfg->damping * b->s.v[MPM_BODY_OMEGA]);
  for (int d = 0; d < b->dim; d++)
    b->s.c[d] += dt * b->s.v[d];
  if (b->s.v[MPM_BODY_OMEGA] != 0.0)
    mpm_body_turned(b, b->s.theta + dt * b->s.v[MPM_BODY_OMEGA]);
}

void mpm_body_turned(mpm_body *b, double theta)
{
  b->s.theta = theta;
  b->ct = cos(theta);
  b->sn = sin(theta);
}

/* ---- reach --------------------------------------------------------------- */

/* The radius about the centre within which the profile lies. */
static double profile_reach(const mpm_body_config *cfg)
{
  switch (cfg->shape) {
  case MPM_BODY_DISC: return cfg->radius;
  case MPM_BODY_BOX: return hypot(cfg->hx, cfg->hy);
  default: {
    double r = 0.0;
    for (int i = 0; i < cfg->nvert; i++)
      r = fmax(r, hypot(cfg->px[i], cfg->py[i]));
    return r;
  }
  }
}

void mpm_body_node_box(const mpm_body *b, const mpm_mesh *m, int lo[3], int hi[3])
{
  const double r = sqrt(b->reach2);
  for (int a = 0; a < 3; a++) {
    lo[a] = 0;
    hi[a] = m->sn[a];
    if (b->cfg->side == MPM_BODY_INSIDE || (a == 2 && m->dim == 2))
      continue;
    double ext = r;                          /* along the axis: half the length */
    if (a == b->e[2])
      ext = b->cfg->length > 0.0 ? 0.5 * b->cfg->length : INFINITY;
    const double l = floor((b->s.c[a] - ext - m->o[a]) * m->ih[a]) - 1.0;
    const double h = ceil((b->s.c[a] + ext - m->o[a]) * m->ih[a]) + 2.0;
    if (l > 0.0)
      lo[a] = l < (double)m->sn[a] ? (int)l : m->sn[a];
    if (h < (double)m->sn[a])
      hi[a] = h > 0.0 ? (int)h : 0;
  }
}

int mpm_body_in_mesh(const mpm_body *b, const mpm_mesh *m)
{
  for (int a = 0; a < m->dim; a++)
    if (!m->periodic[a] && !(b->s.c[a] >= m->o[a] && b->s.c[a] <= m->o[a] + m->len[a]))
      return 0;
  return 1;
}

/* ---- outline ----------------------------------------------------------- */

int mpm_body_outline(const mpm_body *b, const mpm_mesh *m, double *xyz, int *nr, int *caps)
{
  const mpm_body_config *cfg = b->cfg;
  double u[MPM_BODY_OUTLINE_MAX], w[MPM_BODY_OUTLINE_MAX];
  int nv = 0;
  switch (cfg->shape) {
  case MPM_BODY_DISC:
    for (; nv < MPM_BODY_OUTLINE_DISC; nv++) {
      const double a = (2.0 * 3.14159265358979323846 / MPM_BODY_OUTLINE_DISC) * nv;
      u[nv] = cfg->radius * cos(a);
      w[nv] = cfg->radius * sin(a);
    }
    break;
  case MPM_BODY_BOX:
    for (; nv < 4; nv++) {                   /* (-,-), (+,-), (+,+), (-,+) */
      u[nv] = (nv == 1 || nv == 2) ? cfg->hx : -cfg->hx;
      w[nv] = nv >= 2 ? cfg->hy : -cfg->hy;
    }
    break;
  default:
    for (; nv < cfg->nvert; nv++) {
      u[nv] = cfg->px[nv];
      w[nv] = cfg->py[nv];
    }
  }
  double s[2] = {0.0, 0.0};                  /* the ends along the axis */
  *nr = b->dim == 3 ? 2 : 1;
  *caps = b->dim == 3 && cfg->length > 0.0;
  if (b->dim == 3) {
    const int a = b->e[2];
    s[0] = *caps ? b->s.c[a] - 0.5 * cfg->length : m->o[a];
    s[1] = *caps ? b->s.c[a] + 0.5 * cfg->length : m->o[a] + m->len[a];
  }
  for (int r = 0; r < *nr; r++)
    for (int i = 0; i < nv; i++) {
      double *x = xyz + 3 * (r * nv + i);
      x[b->e[0]] = b->s.c[b->e[0]] + b->ct * u[i] - b->sn * w[i];  /* R(theta) (u, w) */
      x[b->e[1]] = b->s.c[b->e[1]] + b->sn * u[i] + b->ct * w[i];
      x[b->e[2]] = s[r];
    }
  return nv;
}
