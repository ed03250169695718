/* test_flow.c: flow diagnostics (diag/flow.h) against values computed by
 * hand or in closed form: Bagnold-shaped profile bins, layer means and mu,
 * front with an isolated point, heap slope and its sloping range, point
 * pressures, derivative of a quadratic, and the nodal smoothing of [DK15]
 * eqs. 4.1-4.3 on a hand-made stencil and on the real uGIMP stencil. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "diag/flow.h"
#include "diag/rough.h"
#include "diag/jam.h"
#include "mesh/mesh.h"
#include "shape/shape.h"

/* Round-off of a handful of operations on O(1) numbers. */
#define RTOL 1e-13

static void ck_close(double got, double want)
{
  double tol = RTOL * (fabs(want) > 1.0 ? fabs(want) : 1.0);
  ck_assert_msg(fabs(got - want) <= tol, "got %.17g, want %.17g", got, want);
}

static size_t push(mpm_points *pts, double x, double y, double vx, double vy, double m)
{
  size_t i;
  ck_assert_int_eq(mpm_points_push(pts, &i), MPM_OK);
  pts->x[i] = x;
  pts->y[i] = y;
  pts->vx[i] = vx;
  pts->vy[i] = vy;
  pts->mass[i] = m;
  pts->vol[i] = m / 1500.0;
  pts->state[i] = MPM_STATE_DENSE;
  return i;
}

/* Points at y = (j + 0.5)/N of a unit layer with vx = 1 - (1 - y)^1.5 (the
 * Bagnold shape), two per height with masses 1 and 3. With 4 bins and N = 40,
 * bin k holds heights j = 10k ... 10k + 9 and its mean is the plain mean of
 * those ten vx values (equal masses per height). */
START_TEST(t_profile_bagnold_bins)
{
  enum { N = 40, NB = 4 };
  mpm_points *pts = mpm_points_alloc(0);
  mpm_err err = {0};
  mpm_profile_bin b[NB];
  for (int j = 0; j < N; j++) {
    double y = (j + 0.5) / N, v = 1.0 - pow(1.0 - y, 1.5);
    push(pts, 0.1, y, v, -2.0 * v, 1.0);
    push(pts, 0.3, y, v, -2.0 * v, 3.0);
  }
  push(pts, 0.2, 1.5, 99.0, 0.0, 1.0);      /* above ymax: left out */
  ck_assert_int_eq(mpm_diag_profile(pts, 0.0, 1.0, NB, b, &err), MPM_OK);
  for (int k = 0; k < NB; k++) {
    double s = 0.0;
    for (int j = 10 * k; j < 10 * k + 10; j++)
      s += 1.0 - pow(1.0 - (j + 0.5) / N, 1.5);
    ck_close(b[k].y, 0.125 + 0.25 * k);
    ck_close(b[k].vx, s / 10.0);
    ck_close(b[k].vy, -2.0 * s / 10.0);
    ck_close(b[k].mass, 40.0);
    ck_assert_uint_eq(b[k].n, 20);
  }
  ck_assert_int_eq(mpm_diag_profile(pts, 1.0, 1.0, NB, b, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_diag_profile(pts, 0.0, 1.0, 0, b, &err), MPM_EINVAL);
  mpm_points_free(pts);
}
END_TEST

/* Two dense points in simple shear, sigma = -p I + tau (e_x e_y + e_y e_x):
 * tau_invariant = |sxy|. Point 0: m 1, p 100, sxy 30, gdot_p 2;
 * point 1: m 3, p 200, sxy -60, gdot_p 0; point 2: disconnected, m 4.
 * All: mu = (1*30 + 3*60)/(1*100 + 3*200) = 0.3;
 * gdot_min = 1: only point 0, mu = 0.3 too; make point 1 differ: sxy -100
 * -> mu(all) = (30 + 300)/700, mu(flowing) = 0.3.
 * vx = (1*2 + 3*3 + 4*(-1))/8 = 7/8; speed = (1*2 + 3*5 + 4*1)/8 with
 * |v| = 2, 5 (3,4), 1. */
START_TEST(t_flow_means)
{
  mpm_points *pts = mpm_points_alloc(0);
  mpm_flow f;
  size_t i = push(pts, 0, 0.5, 2.0, 0.0, 1.0);
  pts->sxx[i] = pts->syy[i] = pts->szz[i] = -100.0;
  pts->sxy[i] = 30.0;
  pts->gdp[i] = 2.0;
  i = push(pts, 0, 0.25, 3.0, 4.0, 3.0);
  pts->sxx[i] = pts->syy[i] = pts->szz[i] = -200.0;
  pts->sxy[i] = -100.0;
  i = push(pts, 0, 0.75, -1.0, 0.0, 4.0);
  pts->state[i] = MPM_STATE_DISCONNECTED;
  mpm_diag_flow(pts, 0.0, &f);
  ck_close(f.mass, 8.0);
  ck_close(f.vx, 7.0 / 8.0);
  ck_close(f.speed, 21.0 / 8.0);
  ck_close(f.mu, 330.0 / 700.0);
  ck_close(f.flow_mass, 4.0);
  ck_close(f.ymax, 0.75);
  mpm_diag_flow(pts, 1.0, &f);
  ck_close(f.mu, 0.3);
  ck_close(f.flow_mass, 1.0);
  mpm_points_free(pts);
}
END_TEST

/* The velocity the dense material moved with between two frames: ids 0
 * (mass 1) and 1 (mass 3) dense in both, moved by +0.1 and -0.3 m in 0.5 s:
 * (0.1 - 0.9) / (4 x 0.5) = -0.4 m/s, whatever their own vy (FLIP velocities
 * the grid never moved them with). Left out: id 2 (disconnected before),
 * id 3 (gone), id 4 (beyond the slots). The store's order may change. */
START_TEST(t_dense_vy_moved)
{
  mpm_points *a = mpm_points_alloc(0), *b = mpm_points_alloc(0);
  const double ya[5] = {1.0, 2.0, 0.5, 3.0, 4.0}, ma[5] = {1.0, 3.0, 2.0, 5.0, 7.0};
  for (int k = 0; k < 5; k++) {
    const size_t i = push(a, 0.0, ya[k], 0.0, 50.0, ma[k]);
    a->id[i] = k;
  }
  a->state[2] = MPM_STATE_DISCONNECTED;
  const int order[4] = {4, 1, 2, 0};                  /* id 3 has left */
  const double dy[5] = {0.1, -0.3, 9.0, 0.0, 9.0};
  for (int k = 0; k < 4; k++) {
    const int id = order[k];
    const size_t i = push(b, 0.0, ya[id] + dy[id], 0.0, 100.0, ma[id]);
    b->id[i] = id;
  }
  int slot[4] = {-1, -1, -1, -1};
  ck_close(mpm_diag_dense_vy_moved(a, b, 0.5, slot, 4), -0.4);
  for (int k = 0; k < 4; k++)
    ck_assert_int_eq(slot[k], -1);                    /* left as found */
  ck_assert(isnan(mpm_diag_dense_vy_moved(a, b, 0.0, slot, 4)));
  b->state[1] = b->state[3] = MPM_STATE_DISCONNECTED;  /* ids 1 and 0 */
  ck_assert(isnan(mpm_diag_dense_vy_moved(a, b, 0.5, slot, 4)));
  mpm_points_free(a);
  mpm_points_free(b);
}
END_TEST

/* [DK-silo] 7.2 on 101 frames at t = k/100: the last tenth is the 11 frames
 * from t = 0.9 on. vbar = 0 at t = 0 (skipped), -1 after, turning to +1 at
 * frame kz: the crossing is halfway, at (kz - 0.5)/100. Points leave at
 * `rate` per frame from frame 90 on (5 per frame before). */
static mpm_jam jam_case(int kz, int rate)
{
  double t[101], v[101];
  size_t n[101];
  n[0] = 100000;
  for (int k = 0; k <= 100; k++) {
    t[k] = k / 100.0;
    v[k] = k == 0 ? 0.0 : k >= kz ? 1.0 : -1.0;
    if (k > 0)
      n[k] = n[k - 1] - (size_t)(k >= 90 ? rate : 5);
  }
  mpm_jam j;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_diag_jam(101, t, v, n, &j, &err), MPM_OK);
  ck_assert_int_eq(j.frames, 11);
  ck_close(j.t_end, 1.0);
  ck_close(j.leaving, rate);
  return j;
}

START_TEST(t_jam_classes)
{
  mpm_jam j = jam_case(96, 0);                     /* crossing at 0.955, nothing leaves */
  ck_close(j.t_zero, 0.955);
  ck_assert_int_eq(j.v_vote, MPM_JAM_STATIC);
  ck_assert_int_eq(j.n_vote, MPM_JAM_STATIC);
  ck_assert_int_eq(j.cls, MPM_JAM_STATIC);
  j = jam_case(91, 1);                             /* crossing at 0.905: in the last tenth; 1 <= 1 */
  ck_assert_int_eq(j.cls, MPM_JAM_STATIC);
  j = jam_case(200, 20);                           /* no crossing, 20 per frame */
  ck_assert(isnan(j.t_zero));
  ck_assert_int_eq(j.cls, MPM_JAM_FLOWING);
  j = jam_case(30, 11);                            /* crossing at 0.295 < 0.5; 11 > 10 */
  ck_assert_int_eq(j.cls, MPM_JAM_FLOWING);
  j = jam_case(71, 0);                             /* crossing at 0.705: unsure */
  ck_assert_int_eq(j.v_vote, MPM_JAM_UNSURE);
  ck_assert_int_eq(j.n_vote, MPM_JAM_STATIC);
  ck_assert_int_eq(j.cls, MPM_JAM_UNSURE);
  j = jam_case(200, 10);                           /* 10 is not > 10 */
  ck_assert_int_eq(j.v_vote, MPM_JAM_FLOWING);
  ck_assert_int_eq(j.n_vote, MPM_JAM_UNSURE);
  ck_assert_int_eq(j.cls, MPM_JAM_UNSURE);
  j = jam_case(96, 20);                            /* the votes disagree */
  ck_assert_int_eq(j.cls, MPM_JAM_UNSURE);
  ck_assert_str_eq(mpm_diag_jam_name(MPM_JAM_STATIC), "static");
  ck_assert_str_eq(mpm_diag_jam_name(MPM_JAM_FLOWING), "flowing");
  ck_assert_str_eq(mpm_diag_jam_name(MPM_JAM_UNSURE), "unsure");
}
END_TEST

/* A crossing interpolated between unequal values, frames without dense
 * material skipped: -3 at t = 0.2, NaN at 0.3, +1 at 0.4: vbar = 0 at
 * 0.2 + 0.2 * 3/4 = 0.35; errors for too few frames, time going back and a
 * count that grows. */
START_TEST(t_jam_crossing_and_errors)
{
  const double t[5] = {0.0, 0.1, 0.2, 0.3, 0.4};
  const double v[5] = {0.0, -1.0, -3.0, NAN, 1.0};
  const size_t n[5] = {10, 10, 9, 9, 9};
  mpm_jam j;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_diag_jam(5, t, v, n, &j, &err), MPM_OK);
  ck_close(j.t_zero, 0.35);
  ck_assert_int_eq(j.frames, 1);                   /* t >= 0.36: the last frame only */
  ck_assert_int_eq(mpm_diag_jam(1, t, v, n, &j, &err), MPM_EINVAL);
  const double tb[3] = {0.0, 0.2, 0.2};
  ck_assert_int_eq(mpm_diag_jam(3, tb, v, n, &j, &err), MPM_EINVAL);
  ck_assert_ptr_nonnull(strstr(err.msg, "frame 2"));
  const size_t ng[3] = {10, 9, 10};
  ck_assert_int_eq(mpm_diag_jam(3, t, v, ng, &j, &err), MPM_EINVAL);
  ck_assert_ptr_nonnull(strstr(err.msg, "more than"));
}
END_TEST

/* Deviatoric normal stresses count in tau: sxx = -p + s, syy = -p - s,
 * szz = -p gives tau = sqrt((s^2 + s^2)/2) = |s|. */
START_TEST(t_flow_mu_normal_deviator)
{
  mpm_points *pts = mpm_points_alloc(0);
  mpm_flow f;
  size_t i = push(pts, 0, 0, 0, 0, 1.0);
  pts->sxx[i] = -50.0 + 20.0;
  pts->syy[i] = -50.0 - 20.0;
  pts->szz[i] = -50.0;
  mpm_diag_flow(pts, 0.0, &f);
  ck_close(f.mu, 0.4);
  mpm_points_free(pts);
}
END_TEST

/* A 10 x 10 block of points with spacing 0.01 from (0.005, 0.005) and one
 * point alone at x = 1: plain front 1; with 0.02 m cells and at least 2
 * points the lone one is isolated and the front is the block's 0.095. */
START_TEST(t_front_isolated)
{
  mpm_points *pts = mpm_points_alloc(0);
  mpm_err err = {0};
  double xf = 0.0;
  for (int j = 0; j < 10; j++)
    for (int k = 0; k < 10; k++)
      push(pts, 0.005 + 0.01 * k, 0.005 + 0.01 * j, 0, 0, 1);
  push(pts, 1.0, 0.005, 0, 0, 1);
  ck_assert_int_eq(mpm_diag_front(pts, 0.02, 1, &xf, &err), MPM_OK);
  ck_close(xf, 1.0);
  ck_assert_int_eq(mpm_diag_front(pts, 0.02, 2, &xf, &err), MPM_OK);
  ck_close(xf, 0.095);
  /* two lone points side by side count as a pair */
  push(pts, 1.005, 0.005, 0, 0, 1);
  ck_assert_int_eq(mpm_diag_front(pts, 0.02, 2, &xf, &err), MPM_OK);
  ck_close(xf, 1.005);
  ck_assert_int_eq(mpm_diag_front(pts, 0.02, 3, &xf, &err), MPM_OK);
  ck_close(xf, 0.095);
  ck_assert_int_eq(mpm_diag_front(pts, 0.0, 3, &xf, &err), MPM_EINVAL);
  mpm_points_free(pts);
}
END_TEST

/* Heap y <= 0.3 - tan(20 deg) x sampled with columns of width 0.01: the top
 * point of each column lies on the surface at the column centre, points
 * below it fill the column. The fitted slope is -tan(20 deg) to round-off,
 * on any sub-range. */
START_TEST(t_heap_slope)
{
  const double s = tan(20.0 * acos(-1.0) / 180.0), w = 0.01;
  mpm_points *pts = mpm_points_alloc(0);
  mpm_err err = {0};
  double slope = 0.0, top[80];
  for (int k = 0; k < 90; k++) {
    double x = (k + 0.5) * w, h = 0.3 - s * x;
    if (h <= 0.0)
      break;
    for (double y = h; y > 0.0; y -= 0.007)
      push(pts, x, y, 0, 0, 1);
  }
  ck_assert_int_eq(mpm_diag_heap_slope(pts, 0.0, 0.6, w, &slope, &err), MPM_OK);
  ck_close(slope, -s);
  ck_assert_int_eq(mpm_diag_heap_slope(pts, 0.2, 0.5, w, &slope, &err), MPM_OK);
  ck_close(slope, -s);
  ck_assert_int_eq(mpm_diag_surface(pts, 0.0, w, 80, top, &err), MPM_OK);
  ck_close(top[3], 0.3 - s * 0.035);
  /* beyond the toe (x > 0.3/s = 0.824) columns are empty (NaN) and skipped */
  ck_assert_int_eq(mpm_diag_surface(pts, 0.8, w, 4, top, &err), MPM_OK);
  ck_close(top[0], 0.3 - s * 0.805);
  ck_assert(isnan(top[2]) && isnan(top[3]));
  ck_assert_int_eq(mpm_diag_heap_slope(pts, 0.7, 0.9, w, &slope, &err), MPM_OK);
  ck_close(slope, -s);
  ck_assert_int_eq(mpm_diag_heap_slope(pts, 0.5, 0.4, w, &slope, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_diag_heap_slope(pts, 0.9, 1.2, w, &slope, &err), MPM_EINVAL);
  mpm_points_free(pts);
}
END_TEST

/* The sloping part of a heap: columns of width 0.5 from x = 2, heights above
 * the base y = 1 of 10, 10, 9.5, 6, 3, 1.5, 0.5, (empty), 0.2. The highest
 * is 10; the first column below 9 is column 3 (6), so xa = 2 + 3 * 0.5 = 3.5;
 * the last above 1 is column 5 (1.5), so xb = 2 + 6 * 0.5 = 5. A point below
 * a column's top and points outside the columns do not count. */
START_TEST(t_slope_range)
{
  const double h[] = {10, 10, 9.5, 6, 3, 1.5, 0.5, NAN, 0.2};
  const double x0 = 2.0, w = 0.5, base = 1.0;
  mpm_points *pts = mpm_points_alloc(0);
  mpm_err err = {0};
  double xa = 0.0, xb = 0.0;
  for (int k = 0; k < 9; k++)
    if (!isnan(h[k]))
      push(pts, x0 + (k + 0.5) * w, base + h[k], 0, 0, 1);
  push(pts, x0 + 3.5 * w, base, 0, 0, 1);   /* below the top of column 3 */
  push(pts, 1.9, 100.0, 0, 0, 1);           /* left of the columns */
  push(pts, 6.6, 100.0, 0, 0, 1);           /* right of the 9 columns */
  ck_assert_int_eq(mpm_diag_slope_range(pts, x0, w, 9, base, &xa, &xb, &err), MPM_OK);
  ck_assert_double_eq(xa, 3.5);
  ck_assert_double_eq(xb, 5.0);
  mpm_points_free(pts);

  /* a step from 4 to 0.2: the last column above 0.4 is left of the first
   * below 3.6, so nothing slopes */
  pts = mpm_points_alloc(0);
  for (int k = 0; k < 4; k++)
    push(pts, (k + 0.5) * w, k < 2 ? 4.0 : 0.2, 0, 0, 1);
  ck_assert_int_eq(mpm_diag_slope_range(pts, 0.0, w, 4, 0.0, &xa, &xb, &err), MPM_EINVAL);
  mpm_points_free(pts);

  /* flat: no column below 90% of the highest */
  pts = mpm_points_alloc(0);
  for (int k = 0; k < 3; k++)
    push(pts, (k + 0.5) * w, 3.0, 0, 0, 1);
  ck_assert_int_eq(mpm_diag_slope_range(pts, 0.0, w, 3, 0.0, &xa, &xb, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_diag_slope_range(pts, 0.0, w, 0, 0.0, &xa, &xb, &err), MPM_EINVAL);
  mpm_points_free(pts);
}
END_TEST

/* p = -(sxx + syy + szz) / 3: (-3, -6, -9) Pa gives 6 Pa, (1, 2, -6) Pa gives 1 Pa. */
START_TEST(t_pressure)
{
  const double s[2][3] = {{-3, -6, -9}, {1, 2, -6}}, want[2] = {6.0, 1.0};
  mpm_points *pts = mpm_points_alloc(0);
  double p[2];
  for (int i = 0; i < 2; i++) {
    size_t k = push(pts, 0, 0, 0, 0, 1);
    pts->sxx[k] = s[i][0];
    pts->syy[k] = s[i][1];
    pts->szz[k] = s[i][2];
    pts->sxy[k] = 5.0;                          /* shear does not enter p */
  }
  mpm_diag_pressure(pts, p);
  ck_assert_double_eq(p[0], want[0]);
  ck_assert_double_eq(p[1], want[1]);
  mpm_points_free(pts);
}
END_TEST

START_TEST(t_line_fit)
{
  const double x[] = {1.0, 2.0, 4.0, 7.0, 3.0};
  double y[5], a = 0, b = 0;
  mpm_err err = {0};
  for (int i = 0; i < 5; i++)
    y[i] = 2.5 - 0.75 * x[i];
  y[3] = NAN;                                /* skipped */
  ck_assert_int_eq(mpm_diag_line_fit(5, x, y, &a, &b, &err), MPM_OK);
  ck_close(a, 2.5);
  ck_close(b, -0.75);
  /* y = 0, 1, 0 at x = 0, 1, 2: b = 0, a = 1/3 */
  const double x3[] = {0, 1, 2}, y3[] = {0, 1, 0};
  ck_assert_int_eq(mpm_diag_line_fit(3, x3, y3, &a, &b, &err), MPM_OK);
  ck_close(a, 1.0 / 3.0);
  ck_close(b, 0.0);
  ck_assert_int_eq(mpm_diag_line_fit(1, x, y, &a, &b, &err), MPM_EINVAL);
}
END_TEST

/* v = 3 t^2 - 2 t + 1 on uneven times: inside, v' = 6 t - 2 exactly; at the
 * ends the one-sided difference is the chord slope 3 (t0 + t1) - 2. */
START_TEST(t_derivative_quadratic)
{
  const double t[] = {0.0, 0.1, 0.35, 0.4, 1.0};
  double v[5], d[5];
  mpm_err err = {0};
  for (int i = 0; i < 5; i++)
    v[i] = 3.0 * t[i] * t[i] - 2.0 * t[i] + 1.0;
  ck_assert_int_eq(mpm_diag_derivative(5, t, v, d, &err), MPM_OK);
  for (int i = 1; i < 4; i++)
    ck_close(d[i], 6.0 * t[i] - 2.0);
  ck_close(d[0], 3.0 * (0.0 + 0.1) - 2.0);
  ck_close(d[4], 3.0 * (0.4 + 1.0) - 2.0);
  const double tb[] = {0.0, 0.0};
  ck_assert_int_eq(mpm_diag_derivative(2, tb, v, d, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_diag_derivative(1, t, v, d, &err), MPM_EINVAL);
}
END_TEST

/* Hand-made stencil: 3 nodes, 2 points.
 *   point 0: m 1, f 10, S = (0.5, 0.5, 0)
 *   point 1: m 3, f 2,  S = (0, 0.25, 0.75)
 * m = (0.5, 1.25, 2.25), (m f) = (5, 5 + 1.5, 4.5) -> f_i = (10, 5.2, 2);
 * out_0 = 0.5*10 + 0.5*5.2 = 7.6, out_1 = 0.25*5.2 + 0.75*2 = 2.8. */
START_TEST(t_smooth_hand)
{
  mpm_shape_stencil *st = mpm_shape_stencil_alloc(2);
  mpm_err err = {0};
  const double mass[] = {1.0, 3.0}, f[] = {10.0, 2.0};
  double nm[3], nmf[3], out[2];
  ck_assert_ptr_nonnull(st);
  st->count[0] = 2;
  st->node[0] = 0;
  st->node[1] = 1;
  st->S[0] = 0.5;
  st->S[1] = 0.5;
  st->count[1] = 2;
  st->node[st->w + 0] = 1;
  st->node[st->w + 1] = 2;
  st->S[st->w + 0] = 0.25;
  st->S[st->w + 1] = 0.75;
  ck_assert_int_eq(mpm_diag_smooth(st, 2, mass, f, 3, nm, nmf, out, &err), MPM_OK);
  ck_close(nm[1], 1.25);
  ck_close(nmf[1], 5.2);
  ck_close(out[0], 7.6);
  ck_close(out[1], 2.8);
  st->node[1] = 7;                          /* node outside 0..2 */
  ck_assert_int_eq(mpm_diag_smooth(st, 2, mass, f, 3, nm, nmf, out, &err), MPM_EINVAL);
  mpm_shape_stencil_free(st);
}
END_TEST

/* With the run's own uGIMP stencil (partition of unity) a constant field is
 * reproduced exactly and the mass-weighted total of a linear field is kept:
 * sum_p m_p out_p = sum_i m_i f_i = sum_p m_p f_p. */
START_TEST(t_smooth_ugimp)
{
  mpm_mesh m = {.nx = 6, .ny = 5, .dx = 0.1, .dy = 0.1};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  mpm_points *pts = mpm_points_alloc(0);
  for (int j = 0; j < 8; j++)
    for (int k = 0; k < 10; k++) {
      size_t i = push(pts, 0.1 + 0.025 * (k + 0.5) + 0.01 * j, 0.1 + 0.025 * (j + 0.5),
                      0, 0, 1.0 + 0.1 * k);
      pts->r1x[i] = pts->r2y[i] = 0.0125;
    }
  mpm_shape_stencil *st = mpm_shape_stencil_alloc(pts->n);
  ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_ugimp, &m, pts, 0.0, &err), MPM_OK);
  double *f = malloc(pts->n * sizeof *f), *out = malloc(pts->n * sizeof *out);
  double *nm = malloc((size_t)m.nnodes * sizeof *nm), *nmf = malloc((size_t)m.nnodes * sizeof *nmf);
  for (size_t i = 0; i < pts->n; i++)
    f[i] = 7.0;
  ck_assert_int_eq(mpm_diag_smooth(st, pts->n, pts->mass, f, m.nnodes, nm, nmf, out, &err),
                   MPM_OK);
  for (size_t i = 0; i < pts->n; i++)
    ck_close(out[i], 7.0);
  double s0 = 0.0, s1 = 0.0;
  for (size_t i = 0; i < pts->n; i++)
    f[i] = 3.0 + 2.0 * pts->x[i] - pts->y[i];
  ck_assert_int_eq(mpm_diag_smooth(st, pts->n, pts->mass, f, m.nnodes, nm, nmf, out, &err),
                   MPM_OK);
  for (size_t i = 0; i < pts->n; i++) {
    s0 += pts->mass[i] * f[i];
    s1 += pts->mass[i] * out[i];
  }
  ck_close(s1, s0);
  free(f);
  free(out);
  free(nm);
  free(nmf);
  mpm_shape_stencil_free(st);
  mpm_points_free(pts);
}
END_TEST


/* Roughness (diag/rough.h), from its definition on hand-made fields.
 *  - A row of points h apart, r = 1.5 h: two neighbours inside, one at the
 *    ends. p = 1 + a (-1)^i: the neighbours of i both hold 1 - a (-1)^i, so
 *    |p_i - median| = 2a everywhere and the mean of p over an even count is
 *    1: roughness = 2a exactly.
 *  - The same row with p linear in x: the median of the two neighbours is
 *    p_i (symmetric), only the two ends differ, by h dp/dx each.
 *  - Disconnected points are neither counted nor neighbours; the dense
 *    fraction counts them. */
static void row(mpm_points *P, int n, double h)
{
  for (int i = 0; i < n; i++) {
    size_t q;
    mpm_points_push(P, &q);
    P->x[q] = i * h;
    P->y[q] = 0.3;
    P->state[q] = MPM_STATE_DENSE;
  }
}

static void set_p(mpm_points *P, size_t q, double p)
{
  P->sxx[q] = P->syy[q] = P->szz[q] = -p;
}

START_TEST(t_roughness)
{
  const int n = 10;
  const double h = 0.01, a = 0.2;
  mpm_points *P = mpm_points_alloc(16);
  row(P, n, h);
  for (int i = 0; i < n; i++)
    set_p(P, (size_t)i, 1.0 + (i % 2 ? -a : a));
  mpm_roughness r;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_diag_roughness(P, 1.5 * h, &r, &err), MPM_OK);
  ck_assert_double_eq_tol(r.roughness, 2.0 * a, 1e-14);
  ck_assert_double_eq_tol(r.mean_p, 1.0, 1e-14);
  ck_assert_uint_eq(r.nused, (size_t)n);
  ck_assert_double_eq(r.dense_fraction, 1.0);
  for (int i = 0; i < n; i++)              /* p = 100 (1 + x) */
    set_p(P, (size_t)i, 100.0 * (1.0 + i * h));
  ck_assert_int_eq(mpm_diag_roughness(P, 1.5 * h, &r, &err), MPM_OK);
  const double mean = 100.0 * (1.0 + 0.5 * (n - 1) * h);
  ck_assert_double_eq_tol(r.roughness, (2.0 * 100.0 * h / n) / mean, 1e-12);
  P->state[3] = MPM_STATE_DISCONNECTED;    /* 2 and 4 keep one neighbour each */
  ck_assert_int_eq(mpm_diag_roughness(P, 1.5 * h, &r, &err), MPM_OK);
  ck_assert_uint_eq(r.ndense, (size_t)n - 1);
  ck_assert_uint_eq(r.nused, (size_t)n - 1);
  ck_assert_double_eq_tol(r.dense_fraction, (n - 1.0) / n, 1e-15);
  ck_assert_double_eq_tol(r.roughness,       /* ends 0, 9 and now 2, 4 off by h dp/dx */
                          (4.0 * 100.0 * h / (n - 1)) / ((n * mean - 100.0 * (1.0 + 3 * h)) / (n - 1)),
                          1e-12);
  ck_assert_int_eq(mpm_diag_roughness(P, 0.0, &r, &err), MPM_EINVAL);
  mpm_points_free(P);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("flow");
  TCase *tc = tcase_create("flow");
  tcase_add_test(tc, t_profile_bagnold_bins);
  tcase_add_test(tc, t_roughness);
  tcase_add_test(tc, t_flow_means);
  tcase_add_test(tc, t_dense_vy_moved);
  tcase_add_test(tc, t_jam_classes);
  tcase_add_test(tc, t_jam_crossing_and_errors);
  tcase_add_test(tc, t_flow_mu_normal_deviator);
  tcase_add_test(tc, t_front_isolated);
  tcase_add_test(tc, t_heap_slope);
  tcase_add_test(tc, t_slope_range);
  tcase_add_test(tc, t_pressure);
  tcase_add_test(tc, t_line_fit);
  tcase_add_test(tc, t_derivative_quadratic);
  tcase_add_test(tc, t_smooth_hand);
  tcase_add_test(tc, t_smooth_ugimp);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
