/* history.c: velocity-gradient histories: the table, the [DK15] App. B table
 * (eq. B1-B2), evaluation and exact step means (reading and writing them as
 * CSV is io/history.c).
 *
 * L(t) = L_k + (t - t_k) / (t_{k+1} - t_k) (L_{k+1} - L_k) on segment k;
 * mean over [a, b] = sum over segments of (v - u) (L(u) + L(v)) / 2 / (b - a),
 * [u, v] the part of [a, b] in the segment (trapezoid rule, exact for linear L). */
#include "pointrun/history.h"

#include <stdlib.h>
#include <string.h>

mpm_history *mpm_pointrun_history_alloc(size_t n)
{
  mpm_history *h = calloc(1, sizeof *h);
  if (!h)
    return NULL;
  h->n = n;
  h->t = calloc(n ? n : 1, sizeof *h->t);
  h->L = calloc(n ? 4 * n : 1, sizeof *h->L);
  if (!h->t || !h->L) {
    mpm_pointrun_history_free(h);
    return NULL;
  }
  return h;
}

void mpm_pointrun_history_free(mpm_history *h)
{
  if (!h)
    return;
  free(h->t);
  free(h->L);
  free(h);
}

/* ------------------------------------------------------- [DK15] App. B */

/* Nodes where the ramps of eq. B2 switch: Lxx = Lyy = -1 at t = 3/8 (L_com),
 * +1 at t = 7/8 (L_ext), 0 at the Heaviside switches; Lxy = 0.05 throughout.
 * A row is t, Lxx, Lxy, Lyx, Lyy. */
static const double dk15_node[][MPM_HISTORY_NCOL] = {
  {0.0, 0, 0.05, 0, 0},     {0.25, 0, 0.05, 0, 0},  {0.375, -1, 0.05, 0, -1},
  {0.5, 0, 0.05, 0, 0},     {0.75, 0, 0.05, 0, 0},  {0.875, 1, 0.05, 0, 1},
  {1.0, 0, 0.05, 0, 0},     {1.25, 0, 0.05, 0, 0},
};

int mpm_pointrun_history_dk15(mpm_history **out, mpm_err *err)
{
  size_t n = sizeof dk15_node / sizeof dk15_node[0];
  mpm_history *h = mpm_pointrun_history_alloc(n);
  if (!h)
    return mpm_err_set(err, MPM_ENOMEM, "dk15 history: out of memory");
  for (size_t k = 0; k < n; k++) {
    h->t[k] = dk15_node[k][0];
    memcpy(h->L + 4 * k, &dk15_node[k][1], 4 * sizeof(double));
  }
  *out = h;
  return MPM_OK;
}

/* ---------------------------------------------------------- evaluation */

size_t mpm_pointrun_history_segment(const mpm_history *h, double t)
{
  size_t lo = 0, hi = h->n - 1;  /* invariant: answer in [lo, hi - 1] */
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (t >= h->t[mid])
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

/* In-plane components into a 3x3 L. */
static mpm_mat3 plane_L(double xx, double xy, double yx, double yy)
{
  return (mpm_mat3){{{xx, xy, 0.0}, {yx, yy, 0.0}, {0.0, 0.0, 0.0}}};
}

mpm_mat3 mpm_pointrun_history_eval_seg(const mpm_history *h, size_t k, double t)
{
  const double *a = h->L + 4 * k, *b = a + 4;
  double w = (t - h->t[k]) / (h->t[k + 1] - h->t[k]);  /* (t - t_k) / (t_{k+1} - t_k) */
  return plane_L(a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1]),
                 a[2] + w * (b[2] - a[2]), a[3] + w * (b[3] - a[3]));
}

mpm_mat3 mpm_pointrun_history_eval(const mpm_history *h, double t)
{
  if (t <= h->t[0])
    return plane_L(h->L[0], h->L[1], h->L[2], h->L[3]);
  if (t >= h->t[h->n - 1]) {
    const double *e = h->L + 4 * (h->n - 1);
    return plane_L(e[0], e[1], e[2], e[3]);
  }
  return mpm_pointrun_history_eval_seg(h, mpm_pointrun_history_segment(h, t), t);
}

/* int_u^v L dt on segment k (trapezoid, exact for linear L), into acc. */
static void add_segment_integral(const mpm_history *h, size_t k, double u, double v,
                                 mpm_mat3 *acc)
{
  mpm_mat3 Lu = mpm_pointrun_history_eval_seg(h, k, u), Lv = mpm_pointrun_history_eval_seg(h, k, v);
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      acc->m[i][j] += 0.5 * (v - u) * (Lu.m[i][j] + Lv.m[i][j]);
}

mpm_mat3 mpm_pointrun_history_mean(const mpm_history *h, double a, double b)
{
  mpm_mat3 acc = plane_L(0, 0, 0, 0);
  double t0 = h->t[0], t1 = h->t[h->n - 1];
  if (a < t0) {  /* constant extension before the first node */
    mpm_mat3 L0 = mpm_pointrun_history_eval(h, t0);
    double v = b < t0 ? b : t0;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++)
        acc.m[i][j] += (v - a) * L0.m[i][j];
  }
  if (b > t1) {  /* constant extension after the last node */
    mpm_mat3 L1 = mpm_pointrun_history_eval(h, t1);
    double u = a > t1 ? a : t1;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++)
        acc.m[i][j] += (b - u) * L1.m[i][j];
  }
  double lo = a > t0 ? a : t0, hi = b < t1 ? b : t1;
  for (size_t k = mpm_pointrun_history_segment(h, lo); lo < hi && k + 1 < h->n; k++) {
    double v = h->t[k + 1] < hi ? h->t[k + 1] : hi;
    if (v > lo)
      add_segment_integral(h, k, lo, v, &acc);
    lo = v;
  }
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      acc.m[i][j] /= (b - a);
  return acc;
}
