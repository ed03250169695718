/* bodies.c: the rigid bodies of a run in the step (bc/body.h; docs/model.md,
 * "Rigid bodies and contact"), for either dimension.
 *
 * After the grid update each node with mass and phi(x_i) <= h/2 of a body
 * (h the shortest unit side: the nodes inside it and those less than half a
 * unit outside, see reach()) has its velocity corrected by the contact rule
 * relative to the body's velocity there (components held by a fixed wall stay held), and its
 * acceleration takes the jump, a_i += (v_i' - v_i)/dt, so that FLIP carries
 * the correction to the points. The material's force on the body is
 * -sum m_i (v_i' - v_i)/dt over those nodes and its torque about the centre
 * the sum of (x_i - c) x that: summed per row of nodes on any number of
 * threads, then row by row in order, so the sums do not depend on the
 * thread count. After the points have moved, a point with phi < 0 is put
 * back on the surface along n and counted; a free (not dense) point also
 * loses its approach to the body, as at a fixed wall. At the end of the step
 * each body moves (mpm_body_advance). */
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "solver/solver.h"
#include "solver/solver_internal.h"

/* Points of the store inside body b (phi < -tol): marked in keep (0) when
 * keep is given; returns their number. */
static size_t overlap(const mpm_sim *s, const mpm_body *b, unsigned char *keep)
{
  const mpm_points *P = s->pts;
  const double tol = 1e-9 * fmin(s->mesh.h[0], s->mesh.h[1]);
  size_t n = 0;
  for (size_t p = 0; p < P->n; p++) {
    const double x[3] = {P->x[p], P->y[p], s->dim == 3 ? P->z[p] : 0.0};
    if (mpm_body_phi(b, x, NULL) < -tol) {
      n++;
      if (keep)
        keep[p] = 0;
    }
  }
  return n;
}

/* The reach of a body: it holds the nodes with phi <= half the shortest
 * unit side. A node nearer the surface than that, outside it, would have
 * most of its support inside the body, where there is no material: the
 * pressure of the thin layer between it and the surface pushes it towards
 * the body with a force that grows as the layer thins, and that layer
 * would be squeezed without bound. */
static double reach(const mpm_mesh *m)
{
  double h = fmin(m->h[0], m->h[1]);
  if (m->dim == 3)
    h = fmin(h, m->h[2]);
  return 0.5 * h;
}

/* The mesh nodes that body b holds (phi <= reach). */
static long nodes_inside(const mpm_sim *s, const mpm_body *b)
{
  const mpm_mesh *m = &s->mesh;
  const double tol = reach(m);
  int lo[3], hi[3];
  long n = 0;
  mpm_body_node_box(b, m, lo, hi);
  for (int k = lo[2]; k < hi[2]; k++)
    for (int j = lo[1]; j < hi[1]; j++)
      for (int i = lo[0]; i < hi[0]; i++) {
        double x[3];
        mpm_mesh_node_pos(m, i, j, k, x);
        n += mpm_body_phi(b, x, NULL) <= tol;
      }
  return n;
}

int mpm_sim_bodies_setup(mpm_sim *s, mpm_err *err)
{
  const mpm_config *cfg = &s->cfg;
  s->nbody = cfg->nbody;
  if (s->nbody == 0)
    return MPM_OK;
  for (int k = 0; k < s->nbody; k++)
    mpm_body_init(&s->body[k], &s->cfg.body[k], s->dim);
  unsigned char *keep = malloc(s->pts->n ? s->pts->n : 1);
  const size_t rows = (size_t)s->mesh.sn[1] * (size_t)s->mesh.sn[2];
  s->brow = malloc(rows * 6 * sizeof *s->brow);
  if (!keep || !s->brow) {
    free(keep);
    return mpm_err_set(err, MPM_ENOMEM, "bodies: out of memory");
  }
  memset(keep, 1, s->pts->n);
  int rc = MPM_OK;
  for (int k = 0; k < s->nbody && rc == MPM_OK; k++) {
    const mpm_body *b = &s->body[k];
    if (!mpm_body_in_mesh(b, &s->mesh)) {
      rc = mpm_err_set(err, MPM_EINPUT, "key 'body.%s.cx': body '%s': its centre lies outside "
                       "the mesh at t = 0", b->cfg->name, b->cfg->name);
      break;
    }
    if (nodes_inside(s, b) == 0) {
      static const char *const size_key[] = {"radius", "hx", "x"};
      rc = mpm_err_set(err, MPM_EINPUT, "key 'body.%s.%s': body '%s' holds no node of the mesh "
                       "at t = 0, so the material would pass through it (allowed: a body that "
                       "reaches within half a unit of a node)", b->cfg->name,
                       size_key[b->cfg->shape], b->cfg->name);
      break;
    }
    const size_t n = overlap(s, b, b->cfg->carve ? keep : NULL);
    if (n > 0 && !b->cfg->carve)
      rc = mpm_err_set(err, MPM_EINPUT, "key 'body.%s.carve': body '%s' overlaps %zu points "
                       "of the fills at t = 0 (allowed: none, or carve = true to leave them out)",
                       b->cfg->name, b->cfg->name, n);
  }
  if (rc == MPM_OK)
    mpm_points_compact(s->pts, keep);
  free(keep);
  return rc;
}

/* The node rows (j, k) of body b's node box, lo and hi its corners. */
static void contact_rows(mpm_sim *s, mpm_body *b, const int lo[3], const int hi[3])
{
  const mpm_mesh *m = &s->mesh;
  const int D = s->dim, lanes = mpm_sim_node_lanes(D);
  const long ny = hi[1] - lo[1], nrow = ny * (hi[2] - lo[2]);
  const double idt = 1.0 / s->dt;
  const double tol = reach(m);
#pragma omp parallel for schedule(static)
  for (long r = 0; r < nrow; r++) {
    const int j = lo[1] + (int)(r % ny), kz = lo[2] + (int)(r / ny);
    double acc[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (int i = lo[0]; i < hi[0]; i++) {
      const int id = (kz * m->sny + j) * m->snx + i;
      const double mi = s->nm[id];
      if (!(mi > s->mtiny))
        continue;
      double x[3], n[3], vb[3];
      mpm_mesh_node_pos(m, i, j, kz, x);
      if (!mpm_body_near(b, x, tol) || mpm_body_phi(b, x, n) > tol)
        continue;
      double *q = s->nq + (size_t)lanes * (size_t)id;
      double v[3] = {q[0], q[1], D == 3 ? q[2] : 0.0}, dv[3] = {0.0, 0.0, 0.0};
      mpm_body_velocity_at(b, x, vb);
      if (!mpm_body_contact(b->cfg, D, vb, n, v))
        continue;
      for (int d = 0; d < D; d++)
        dv[d] = v[d] - q[d];
      if (s->bc.fix[id])                       /* a fixed wall's components stay held */
        mpm_bc_apply_node(&s->bc, id, D, dv);
      double fb[3] = {0.0, 0.0, 0.0}, rx[3];
      for (int d = 0; d < D; d++) {
        q[d] += dv[d];
        q[D + d] += dv[d] * idt;
        fb[d] = -mi * dv[d] * idt;             /* the node's push on the body */
      }
      for (int d = 0; d < 3; d++)
        rx[d] = x[d] - b->s.c[d];
      acc[0] += fb[0];
      acc[1] += fb[1];
      acc[2] += fb[2];
      acc[3] += rx[1] * fb[2] - rx[2] * fb[1];
      acc[4] += rx[2] * fb[0] - rx[0] * fb[2];
      acc[5] += rx[0] * fb[1] - rx[1] * fb[0];
    }
    memcpy(s->brow + 6 * r, acc, sizeof acc);
  }
  double sum[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  for (long r = 0; r < nrow; r++)
    for (int c = 0; c < 6; c++)
      sum[c] += s->brow[6 * r + c];
  for (int d = 0; d < 3; d++) {
    b->s.f[d] = sum[d];
    b->s.tq[d] = sum[3 + d];
  }
}

void mpm_sim_bodies_contact(mpm_sim *s)
{
  for (int k = 0; k < s->nbody; k++) {
    mpm_body *b = &s->body[k];
    int lo[3], hi[3];
    mpm_body_prescribe(b, s->t, s->dt);
    mpm_body_node_box(b, &s->mesh, lo, hi);
    for (int d = 0; d < 3; d++)
      b->s.f[d] = b->s.tq[d] = 0.0;
    if (lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2])
      contact_rows(s, b, lo, hi);
  }
}

void mpm_sim_bodies_points(mpm_sim *s)
{
  mpm_points *P = s->pts;
  const long n = (long)P->n;
  const int D = s->dim;
  for (int k = 0; k < s->nbody; k++) {
    const mpm_body *b = &s->body[k];
    long pushed = 0;
#pragma omp parallel for schedule(static) reduction(+ : pushed)
    for (long p = 0; p < n; p++) {
      double x[3] = {P->x[p], P->y[p], D == 3 ? P->z[p] : 0.0}, nv[3];
      if (!mpm_body_near(b, x, 0.0))
        continue;
      const double phi = mpm_body_phi(b, x, nv);
      if (!(phi < 0.0))
        continue;
      for (int d = 0; d < D; d++)
        P->pos[d][p] = x[d] - phi * nv[d];      /* onto the surface */
      pushed++;
      if (P->state[p] == MPM_STATE_DENSE)
        continue;
      double vb[3], wn = 0.0;                   /* a free point: no approach */
      mpm_body_velocity_at(b, x, vb);
      for (int d = 0; d < D; d++)
        wn += (P->vel[d][p] - vb[d]) * nv[d];
      if (wn < 0.0)
        for (int d = 0; d < D; d++)
          P->vel[d][p] -= wn * nv[d];
    }
    s->body[k].s.npushed += pushed;
  }
}

int mpm_sim_bodies_advance(mpm_sim *s, const double g[3], mpm_err *err)
{
  for (int k = 0; k < s->nbody; k++) {
    mpm_body *b = &s->body[k];
    mpm_body_advance(b, s->dt, g);
    if (!mpm_body_in_mesh(b, &s->mesh))
      return mpm_err_set(err, MPM_EOUTSIDE, "body '%s' left the mesh: its centre at (%.6g, %.6g, "
                         "%.6g) m, t = %.6g s", b->cfg->name, b->s.c[0], b->s.c[1], b->s.c[2],
                         s->t + s->dt);
  }
  return MPM_OK;
}

void mpm_sim_bodies_state(const mpm_sim *s, mpm_body_state *st)
{
  for (int k = 0; k < s->nbody; k++)
    st[k] = s->body[k].s;
}

void mpm_sim_bodies_set(mpm_sim *s, const mpm_body_state *st)
{
  for (int k = 0; k < s->nbody; k++) {
    s->body[k].s = st[k];
    mpm_body_turned(&s->body[k], st[k].theta);
  }
}
