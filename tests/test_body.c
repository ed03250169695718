/* test_body.c: rigid bodies (bc/body.h) against closed forms. The signed
 * distance of a disc, a turned box, a polygon (a turned square against the
 * box) and a finite 3D cylinder at points whose distances are known by hand,
 * with their normals and the sign of each material side, and the gradient
 * against central differences of phi; the contact rule's four cases with
 * exact numbers (noslip, frictionless, friction sticking and sliding, a
 * separating node untouched); the velocity tables (interpolation, ends, a
 * constant); a body's velocity at a point (v + omega a x r) about each
 * axis; free motion: N steps of symplectic Euler under gravity from rest
 * give v = N g dt and c = c0 + g dt^2 N (N + 1)/2 exactly, and damping with
 * an applied force approaches the terminal speed F/(m k); a prescribed
 * table moves the centre by the exact integral of a linear velocity. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bc/body.h"
#include "core/config.h"

static mpm_body_config base(int shape)
{
  mpm_body_config c;
  memset(&c, 0, sizeof c);
  c.shape = shape;
  c.axis = 2;
  c.cx = 1.0;
  c.cy = 2.0;
  c.cz = 3.0;
  for (int k = 0; k < MPM_BODY_NDOF; k++)
    c.nval[k] = 1;
  strcpy(c.name, "b");
  return c;
}

#define NEAR(a, b, tol) ck_assert_msg(fabs((a) - (b)) <= (tol), "%s = %.17g, expected %.17g", #a, \
                                      (double)(a), (double)(b))

/* grad phi by central differences at x. */
static void fd_gradient(const mpm_body *b, const double x[3], double g[3])
{
  const double h = 1e-7;
  for (int d = 0; d < 3; d++) {
    double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
    xp[d] += h;
    xm[d] -= h;
    g[d] = b->dim == 2 && d == 2 ? 0.0
                                 : (mpm_body_phi(b, xp, NULL) - mpm_body_phi(b, xm, NULL)) / (2 * h);
  }
}

START_TEST(disc_distance_and_normal)
{
  mpm_body_config c = base(MPM_BODY_DISC);
  c.radius = 0.5;
  mpm_body b;
  mpm_body_init(&b, &c, 2);
  double n[3];
  const double x[3] = {1.0 + 0.6, 2.0 + 0.8, 0.0};          /* r = 1 */
  NEAR(mpm_body_phi(&b, x, n), 0.5, 1e-15);
  NEAR(n[0], 0.6, 1e-15);
  NEAR(n[1], 0.8, 1e-15);
  ck_assert(n[2] == 0.0);
  const double in[3] = {1.0 - 0.3, 2.0, 0.0};
  NEAR(mpm_body_phi(&b, in, n), -0.2, 1e-15);
  NEAR(n[0], -1.0, 1e-15);
  c.side = MPM_BODY_INSIDE;                                  /* the material inside */
  NEAR(mpm_body_phi(&b, x, n), -0.5, 1e-15);
  NEAR(n[0], -0.6, 1e-15);
  NEAR(n[1], -0.8, 1e-15);
  NEAR(mpm_body_phi(&b, in, NULL), 0.2, 1e-15);
}
END_TEST

START_TEST(turned_box_and_polygon)
{
  mpm_body_config c = base(MPM_BODY_BOX);
  c.hx = 0.4;
  c.hy = 0.1;
  c.angle = 90.0;                                            /* long side along y */
  mpm_body b;
  mpm_body_init(&b, &c, 2);
  double n[3];
  const double side[3] = {1.0 + 0.3, 2.0 + 0.2, 0.0};       /* 0.2 beyond the side x = +0.1 */
  NEAR(mpm_body_phi(&b, side, n), 0.2, 1e-12);
  NEAR(n[0], 1.0, 1e-12);
  NEAR(n[1], 0.0, 1e-12);
  const double corner[3] = {1.0 + 0.1 + 0.3, 2.0 + 0.4 + 0.4, 0.0};
  NEAR(mpm_body_phi(&b, corner, n), 0.5, 1e-12);             /* 3-4-5 from the corner */
  NEAR(n[0], 0.6, 1e-12);
  NEAR(n[1], 0.8, 1e-12);
  const double inside[3] = {1.0 + 0.05, 2.0 - 0.1, 0.0};     /* 0.05 from the side x = +0.1 */
  NEAR(mpm_body_phi(&b, inside, n), -0.05, 1e-12);
  NEAR(n[0], 1.0, 1e-12);
  /* the same rectangle as a polygon turned 30 degrees, against the box */
  mpm_body_config p = base(MPM_BODY_POLYGON), q = c;
  const double px[4] = {-0.4, 0.4, 0.4, -0.4}, py[4] = {-0.1, -0.1, 0.1, 0.1};
  p.nvert = 4;
  memcpy(p.px, px, sizeof px);
  memcpy(p.py, py, sizeof py);
  p.angle = q.angle = 30.0;
  mpm_body bp, bq;
  mpm_body_init(&bp, &p, 2);
  mpm_body_init(&bq, &q, 2);
  for (int i = 0; i < 200; i++) {
    const double x[3] = {1.0 - 0.7 + 0.007 * i, 2.0 - 0.5 + 0.0053 * (i % 37) * 5, 0.0};
    double np[3], nq[3], g[3];
    const double dp = mpm_body_phi(&bp, x, np), dq = mpm_body_phi(&bq, x, nq);
    NEAR(dp, dq, 1e-12);
    fd_gradient(&bq, x, g);
    for (int d = 0; d < 2; d++) {
      NEAR(np[d], nq[d], 1e-9);
      NEAR(nq[d], g[d], 1e-5);
    }
  }
}
END_TEST

START_TEST(finite_cylinder_in_3d)
{
  mpm_body_config c = base(MPM_BODY_DISC);
  c.axis = 1;                                                /* along y: profile (z, x) */
  c.radius = 0.3;
  c.length = 1.0;
  mpm_body b;
  mpm_body_init(&b, &c, 3);
  ck_assert(b.e[0] == 2 && b.e[1] == 0 && b.e[2] == 1);
  double n[3];
  const double end[3] = {1.0 + 0.1, 2.0 + 0.9, 3.0};         /* 0.4 above the end cap */
  NEAR(mpm_body_phi(&b, end, n), 0.4, 1e-15);
  NEAR(n[1], 1.0, 1e-15);
  const double rim[3] = {1.0 + 0.6, 2.0 + 0.9, 3.0};         /* (0.3, 0.4) from the rim */
  NEAR(mpm_body_phi(&b, rim, n), 0.5, 1e-15);
  NEAR(n[0], 0.6, 1e-15);
  NEAR(n[1], 0.8, 1e-15);
  const double in[3] = {1.0, 2.0 + 0.45, 3.0 + 0.1};         /* nearer the cap (0.05) */
  NEAR(mpm_body_phi(&b, in, n), -0.05, 1e-15);
  NEAR(n[1], 1.0, 1e-15);
  for (int i = 0; i < 100; i++) {
    const double x[3] = {1.0 + 0.011 * i - 0.5, 2.0 + 0.017 * i - 0.8, 3.0 + 0.3 - 0.007 * i};
    double g[3];
    mpm_body_phi(&b, x, n);
    fd_gradient(&b, x, g);
    for (int d = 0; d < 3; d++)
      NEAR(n[d], g[d], 1e-5);
  }
  c.length = 0.0;                                            /* through the mesh */
  NEAR(mpm_body_phi(&b, end, NULL), -0.2, 1e-15);
}
END_TEST

/* The outline's vertices lie on the surface (phi = 0 to round-off) for a
 * turned disc, box and polygon in the plane and a turned box prism of finite
 * length in 3D (its end rings on the rims of the caps), in order around the
 * profile (consecutive vertices a side apart for the box), with the ring
 * and cap counts of each case; a 3D body through the mesh ends on the
 * mesh's faces, with open ends. */
START_TEST(outline_on_the_surface)
{
  mpm_mesh m;
  memset(&m, 0, sizeof m);
  m.dim = 3;
  m.o[2] = -1.0;
  m.len[2] = 5.0;
  double xyz[2 * 3 * MPM_BODY_OUTLINE_MAX];
  for (int dim = 2; dim <= 3; dim++)
    for (int shape = MPM_BODY_DISC; shape <= MPM_BODY_POLYGON; shape++) {
      mpm_body_config c = base(shape);
      c.radius = 0.3;
      c.hx = 0.4;
      c.hy = 0.1;
      c.nvert = 3;
      c.px[0] = -0.2; c.py[0] = 0.0;
      c.px[1] = 0.3;  c.py[1] = -0.1;
      c.px[2] = 0.1;  c.py[2] = 0.25;
      c.angle = 30.0;
      c.length = dim == 3 && shape != MPM_BODY_DISC ? 0.8 : 0.0;
      mpm_body b;
      mpm_body_init(&b, &c, dim);
      int nr = 0, caps = -1;
      const int nv = mpm_body_outline(&b, &m, xyz, &nr, &caps);
      const int want = shape == MPM_BODY_DISC ? MPM_BODY_OUTLINE_DISC : shape == MPM_BODY_BOX ? 4 : 3;
      ck_assert_int_eq(nv, want);
      ck_assert_int_eq(nr, dim == 3 ? 2 : 1);
      ck_assert_int_eq(caps, c.length > 0.0);
      for (int k = 0; k < nr * nv; k++) {
        const double *x = xyz + 3 * k;
        NEAR(mpm_body_phi(&b, x, NULL), 0.0, 1e-14);
        if (dim == 2)
          ck_assert(x[2] == 0.0);
      }
      if (shape == MPM_BODY_BOX)                /* sides 2 hx, 2 hy, 2 hx, 2 hy */
        for (int i = 0; i < 4; i++) {
          const double *p = xyz + 3 * i, *q = xyz + 3 * ((i + 1) % 4);
          NEAR(hypot(q[0] - p[0], q[1] - p[1]), i % 2 ? 0.2 : 0.8, 1e-14);
        }
      if (dim == 3) {                           /* the ends along z */
        const double lo = c.length > 0.0 ? 3.0 - 0.4 : -1.0, hi = c.length > 0.0 ? 3.4 : 4.0;
        NEAR(xyz[2], lo, 1e-15);
        NEAR(xyz[3 * nv + 2], hi, 1e-15);
      }
    }
}
END_TEST

START_TEST(contact_rule)
{
  mpm_body_config c = base(MPM_BODY_DISC);
  const double vb[3] = {1.0, 0.0, 0.0}, n[3] = {0.0, 1.0, 0.0};
  double v[3] = {4.0, -2.0, 0.0};                            /* w = (3, -2): approaching */
  ck_assert(mpm_body_contact(&c, 2, vb, n, v) == 1);
  ck_assert(v[0] == 1.0 && v[1] == 0.0);                     /* noslip: the body's */
  c.contact = MPM_CONTACT_FRICTIONLESS;
  double f[3] = {4.0, -2.0, 0.0};
  mpm_body_contact(&c, 2, vb, n, f);
  ck_assert(f[0] == 4.0 && f[1] == 0.0);
  c.contact = MPM_CONTACT_FRICTION;
  c.friction = 0.5;                                          /* mu |w_n| = 1 < |w_t| = 3 */
  double s[3] = {4.0, -2.0, 0.0};
  mpm_body_contact(&c, 2, vb, n, s);
  NEAR(s[0], 1.0 + 2.0, 1e-15);
  NEAR(s[1], 0.0, 1e-15);
  c.friction = 2.0;                                          /* mu |w_n| = 4 >= 3: sticks */
  double k[3] = {4.0, -2.0, 0.0};
  mpm_body_contact(&c, 2, vb, n, k);
  ck_assert(k[0] == 1.0 && k[1] == 0.0);
  double away[3] = {4.0, 0.5, 0.0};                          /* separating: untouched */
  c.contact = MPM_CONTACT_NOSLIP;
  ck_assert(mpm_body_contact(&c, 2, vb, n, away) == 0);
  ck_assert(away[0] == 4.0 && away[1] == 0.5);
  const double n3[3] = {0.0, 0.0, -1.0}, vb3[3] = {0.0, 0.0, 0.0};
  double v3[3] = {1.0, 2.0, 3.0};                            /* 3D, frictionless */
  c.contact = MPM_CONTACT_FRICTIONLESS;
  mpm_body_contact(&c, 3, vb3, n3, v3);
  ck_assert(v3[0] == 1.0 && v3[1] == 2.0 && v3[2] == 0.0);
}
END_TEST

START_TEST(tables_and_rotation)
{
  mpm_body_config c = base(MPM_BODY_DISC);
  c.ntable = 3;
  c.t[0] = 1.0;
  c.t[1] = 2.0;
  c.t[2] = 4.0;
  c.nval[MPM_BODY_VX] = 3;
  c.val[MPM_BODY_VX][0] = 0.0;
  c.val[MPM_BODY_VX][1] = 1.0;
  c.val[MPM_BODY_VX][2] = -1.0;
  c.val[MPM_BODY_OMEGA][0] = 2.0;                            /* a constant */
  NEAR(mpm_body_table(&c, MPM_BODY_VX, 0.0), 0.0, 0.0);
  NEAR(mpm_body_table(&c, MPM_BODY_VX, 1.5), 0.5, 1e-15);
  NEAR(mpm_body_table(&c, MPM_BODY_VX, 3.0), 0.0, 1e-15);
  NEAR(mpm_body_table(&c, MPM_BODY_VX, 9.0), -1.0, 0.0);
  NEAR(mpm_body_table(&c, MPM_BODY_OMEGA, 3.0), 2.0, 0.0);
  mpm_body b;
  mpm_body_init(&b, &c, 2);
  const double x[3] = {1.0 + 0.5, 2.0 + 0.25, 0.0};
  double vb[3];
  mpm_body_velocity_at(&b, x, vb);                           /* omega z x r = 2 (-0.25, 0.5) */
  NEAR(vb[0], -0.5, 1e-15);
  NEAR(vb[1], 1.0, 1e-15);
  c.axis = 0;                                                /* 3D about x: (y, z) */
  mpm_body_init(&b, &c, 3);
  const double y[3] = {1.0, 2.0 + 0.5, 3.0 + 0.25};
  mpm_body_velocity_at(&b, y, vb);                           /* x r = (0, -r_z, r_y) */
  NEAR(vb[1], -0.5, 1e-15);
  NEAR(vb[2], 1.0, 1e-15);
  /* the centre over the table: the integral of v, exact over linear pieces */
  c.axis = 2;
  c.val[MPM_BODY_OMEGA][0] = 0.0;
  mpm_body_init(&b, &c, 2);
  const double g[3] = {0.0, -9.81, 0.0}, dt = 0.01;
  for (int i = 0; i < 400; i++) {
    mpm_body_prescribe(&b, i * dt, dt);
    mpm_body_advance(&b, dt, g);                             /* not free: no gravity */
  }
  NEAR(b.s.c[0], 1.0 + 0.5 + 0.0, 1e-12);                      /* 0.5 up to t = 2, 0 after */
  NEAR(b.s.c[1], 2.0, 0.0);
}
END_TEST

START_TEST(free_motion)
{
  mpm_body_config c = base(MPM_BODY_DISC);
  c.radius = 0.1;
  c.free[MPM_BODY_VY] = 1;
  c.mass = 2.0;
  mpm_body b;
  mpm_body_init(&b, &c, 2);
  const double g[3] = {0.0, -8.0, 0.0}, dt = 0.125;          /* binary fractions: exact */
  const int N = 20;
  for (int i = 0; i < N; i++)
    mpm_body_advance(&b, dt, g);
  ck_assert(b.s.v[MPM_BODY_VY] == N * -8.0 * dt);
  ck_assert(b.s.c[1] == 2.0 + -8.0 * dt * dt * N * (N + 1) / 2);
  ck_assert(b.s.c[0] == 1.0);
  /* an applied force against damping: v -> F / (m k) */
  mpm_body_config d = base(MPM_BODY_DISC);
  d.free[MPM_BODY_VX] = d.free[MPM_BODY_OMEGA] = 1;
  d.mass = 2.0;
  d.inertia = 0.5;
  d.force[0] = 3.0;
  d.torque = 1.0;
  d.damping = 4.0;
  mpm_body_init(&b, &d, 2);
  const double g0[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < 10000; i++)                           /* (1 - k dt)^N = e^-40 */
    mpm_body_advance(&b, 1e-3, g0);
  NEAR(b.s.v[MPM_BODY_VX], 3.0 / (2.0 * 4.0), 1e-12);
  NEAR(b.s.v[MPM_BODY_OMEGA], 1.0 / (0.5 * 4.0), 1e-12);
  NEAR(cos(b.s.theta), b.ct, 0.0);
}
END_TEST

/* mpm_body_near never rules out a point with phi <= margin: every shape,
 * side and dimension at scattered points. */
START_TEST(near_is_a_safe_filter)
{
  const int shapes[3] = {MPM_BODY_DISC, MPM_BODY_BOX, MPM_BODY_POLYGON};
  int ruled = 0;
  for (int k = 0; k < 12; k++) {
    mpm_body_config c = base(shapes[k % 3]);
    c.radius = 0.3;
    c.hx = 0.3;
    c.hy = 0.1;
    const double px[3] = {-0.2, 0.3, 0.0}, py[3] = {-0.1, 0.0, 0.25};
    c.nvert = 3;
    memcpy(c.px, px, sizeof px);
    memcpy(c.py, py, sizeof py);
    c.side = (k / 3) % 2 ? MPM_BODY_INSIDE : MPM_BODY_OUTSIDE;
    c.angle = 25.0;
    c.length = k >= 6 ? 0.4 : 0.0;
    mpm_body b;
    mpm_body_init(&b, &c, k >= 6 ? 3 : 2);
    for (int i = 0; i < 4000; i++) {
      const double x[3] = {1.0 - 0.6 + 1.2 * ((i * 37) % 101) / 100.0,
                           2.0 - 0.6 + 1.2 * ((i * 53) % 97) / 96.0,
                           3.0 - 0.5 + ((i * 17) % 89) / 88.0};
      for (int m = 0; m < 3; m++) {
        const double margin = 0.05 * m;
        if (!mpm_body_near(&b, x, margin)) {
          ruled++;
          ck_assert_msg(mpm_body_phi(&b, x, NULL) > margin, "body %d, point %d", k, i);
        }
      }
    }
  }
  ck_assert(ruled > 10000);                                  /* it does filter */
}
END_TEST

int main(void)
{
  Suite *s = suite_create("body");
  TCase *tc = tcase_create("body");
  tcase_add_test(tc, disc_distance_and_normal);
  tcase_add_test(tc, turned_box_and_polygon);
  tcase_add_test(tc, finite_cylinder_in_3d);
  tcase_add_test(tc, outline_on_the_surface);
  tcase_add_test(tc, contact_rule);
  tcase_add_test(tc, tables_and_rotation);
  tcase_add_test(tc, free_motion);
  tcase_add_test(tc, near_is_a_safe_filter);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
