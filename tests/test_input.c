/* test_input.c: the input reader (src/io/input*.c): defaults, every key parsed,
 * --set overrides, write -> load round trips, one exact message for every
 * class of bad input (each file in tests/inputs/bad carries its message on an
 * "# expect:" line; one ending in "..." is a prefix, for lists of names that
 * other modules own), and docs/input-reference.md against the reader. The
 * body sections in detail: test_input_body.c. */
#define _POSIX_C_SOURCE 200809L
#include <check.h>
#include <ctype.h>
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/config.h"
#include "core/error.h"
#include "io/io.h"
#include "material/density.h"

#define TMP_DIR "test_input.tmp"
#include "input_case.h"

#define BAD_GLOB TEST_SRCDIR "/tests/inputs/bad/*.conf"
#define DOCS TEST_SRCDIR "/docs/input-reference.md"

/* ------------------------------------------------------------------ helpers */

/* Load path (+ overrides), write, load the written text: the same config. */
static void round_trip(const char *path, const char *const *sets, int nsets)
{
  mpm_config a, b;
  load_ok(path, sets, nsets, &a);
  char *text = written(&a);
  write_bytes(CASE, text, strlen(text));
  load_ok(CASE, NULL, 0, &b);
  memcpy(b.source, a.source, sizeof a.source);
  ck_assert_msg(memcmp(&a, &b, sizeof a) == 0, "%s: round trip changed the config:\n%s", path,
                text);
  char *again = written(&b);
  ck_assert_str_eq(again, text);  /* and writing is stable */
  free(again);
  free(text);
}

/* ----------------------------------------------------------------- defaults */

START_TEST(t_defaults)
{
  mpm_config c;
  memset(&c, 0x5a, sizeof c);
  mpm_io_input_defaults(&c);
  ck_assert_int_eq(c.mesh.nx, 0);
  ck_assert_double_eq(c.mesh.x0, 0.0);
  ck_assert_str_eq(c.mesh.topology, "q4");
  ck_assert_str_eq(c.mesh.diagonal, "/");
  ck_assert_str_eq(c.mesh.shape, "ugimp");
  ck_assert_double_eq(c.time.dt, 0.0);
  ck_assert_double_eq(c.time.cfl, 0.5);
  ck_assert_double_eq(c.time.frame_dt, 0.01);
  ck_assert_double_eq(c.gravity.gx, 0.0);
  ck_assert_double_eq(c.gravity.gy, -9.8);
  ck_assert_double_eq(c.gravity.t_ramp, 0.1);
  ck_assert_str_eq(c.material.model, "mu_i");
  ck_assert_double_eq(c.material.E, 1e9);
  ck_assert_double_eq(c.material.nu, 0.3);
  ck_assert_double_eq(c.material.rho_s, 2450);
  ck_assert_double_eq(c.material.rho_c, 1500);
  ck_assert_double_eq(c.material.mu_s, 0.3819);
  ck_assert_double_eq(c.material.mu_2, 0.6435);
  ck_assert_double_eq(c.material.I0, 0.279);
  ck_assert_double_eq(c.material.d, 0.005);
  ck_assert_double_eq(c.material.A, 0.48);
  ck_assert_double_eq(c.material.t0, 1e-3);
  ck_assert_int_eq(c.bc.left, MPM_BC_FREE);
  ck_assert_int_eq(c.bc.right, MPM_BC_FREE);
  ck_assert_int_eq(c.bc.bottom, MPM_BC_FREE);
  ck_assert_int_eq(c.bc.top, MPM_BC_FREE);
  ck_assert_int_eq(c.nfill, 0);
  ck_assert_str_eq(c.output.dir, "run");
  ck_assert_str_eq(c.source, "");
  /* xi = I0 / (d sqrt(rho_s)) = 1.1273 sqrt(m/kg), [DK15] Table 1 gives 1.1233 */
  ck_assert_double_eq_tol(c.material.I0 / (c.material.d * sqrt(c.material.rho_s)), 1.1233, 0.005);
}
END_TEST

START_TEST(t_minimal)
{
  mpm_config c;
  load_ok(GOOD "minimal.conf", NULL, 0, &c);
  ck_assert_str_eq(c.source, GOOD "minimal.conf");
  ck_assert_int_eq(c.mesh.nx, 8);
  ck_assert_int_eq(c.mesh.ny, 4);
  ck_assert_double_eq(c.mesh.dx, 0.25);
  ck_assert_double_eq(c.mesh.dy, 0.25);
  ck_assert_double_eq(c.time.t_end, 0.5);
  ck_assert_int_eq(c.nfill, 1);
  const mpm_fill_config *f = &c.fill[0];
  ck_assert_str_eq(f->name, "pile");
  ck_assert_int_eq(f->shape, MPM_FILL_RECTANGLE);
  ck_assert_double_eq(f->xmax, 1.0);
  ck_assert_double_eq(f->ymax, 0.5);
  ck_assert_int_eq(f->ppu, 2);
  ck_assert_double_eq(f->density, c.material.rho_c);  /* default: rho_c */
  ck_assert_int_eq(f->lithostatic, 0);
  /* everything else as mpm_io_input_defaults */
  mpm_config d;
  mpm_io_input_defaults(&d);
  ck_assert_mem_eq(&c.time.cfl, &d.time.cfl, sizeof d.time.cfl);
  ck_assert_mem_eq(&c.gravity, &d.gravity, sizeof d.gravity);
  ck_assert_mem_eq(&c.material, &d.material, sizeof d.material);
  ck_assert_mem_eq(&c.bc, &d.bc, sizeof d.bc);
  ck_assert_mem_eq(&c.output, &d.output, sizeof d.output);
}
END_TEST

/* The scheme's defaults follow the run (docs/input-reference.md, "The
 * scheme"): the clean-field options where they exist, the next best where
 * not, the step halved where delta weights need it, and a key the input
 * sets is kept. */
static void check_scheme(const char *const *sets, int nsets, int dilatation, int density,
                         int transfer)
{
  mpm_config c;
  load_ok(GOOD "minimal.conf", sets, nsets, &c);
  ck_assert_int_eq(c.mesh.dilatation, dilatation);
  ck_assert_int_eq(c.material.state_density, density);
  ck_assert_int_eq(c.time.transfer, transfer);
}

START_TEST(t_scheme_defaults)
{
  const int P = MPM_DILATATION_POINT, U = MPM_DILATATION_UNIT, E = MPM_DILATATION_ELEMENT;
  const int DU = MPM_DENSITY_UNIT, DP = MPM_DENSITY_POINT;
  const int F = MPM_TRANSFER_FLIP, A = MPM_TRANSFER_APIC;
  check_scheme(NULL, 0, E, DU, A);  /* plane q4 */
  const char *t3[] = {"mesh.topology=t3"};
  check_scheme(t3, 1, U, DU, A);
  const char *box[] = {"mesh.nz=2", "mesh.dz=0.25", "fill.pile.zmin=0", "fill.pile.zmax=0.5"};
  check_scheme(box, 4, E, DU, A);
  const char *box_narrow[] = {"mesh.nz=2", "mesh.dz=0.25", "fill.pile.zmin=0",
                              "fill.pile.zmax=0.5", "boundary.front=periodic",
                              "boundary.back=periodic"};
  check_scheme(box_narrow, 6, E, DU, F);  /* uGIMP's APIC: 4 units along periodic z */
  /* uGIMP's APIC needs 4 units on a periodic axis, delta's 2 */
  const char *narrow[] = {"boundary.left=periodic", "boundary.right=periodic", "mesh.nx=3",
                          "fill.pile.xmax=0.75"};
  check_scheme(narrow, 4, E, DU, F);
  const char *narrow_delta[] = {"boundary.left=periodic", "boundary.right=periodic",
                                "mesh.nx=3", "fill.pile.xmax=0.75", "mesh.shape=delta"};
  check_scheme(narrow_delta, 5, E, DU, A);
  const char *wide[] = {"boundary.left=periodic", "boundary.right=periodic"};
  check_scheme(wide, 2, E, DU, A);
  const char *blend[] = {"time.flip=0.99"};
  check_scheme(blend, 1, E, DU, F);
  const char *paper[] = {"mesh.dilatation=point", "material.state_density=point",
                         "time.transfer=flip"};
  check_scheme(paper, 3, P, DP, F);
  const char *kept[] = {"mesh.topology=t3", "mesh.dilatation=point", "time.flip=0.99",
                        "time.transfer=apic"};
  check_scheme(kept, 4, P, DU, A);
  /* delta weights under the affine transfer and a per-unit rule: half the step */
  mpm_config c;
  const char *delta[] = {"mesh.shape=delta"};
  load_ok(GOOD "minimal.conf", delta, 1, &c);
  ck_assert_double_eq(c.time.cfl, 0.25);
  const char *delta_flip[] = {"mesh.shape=delta", "time.transfer=flip"};
  load_ok(GOOD "minimal.conf", delta_flip, 2, &c);
  ck_assert_double_eq(c.time.cfl, 0.5);
  const char *delta_point[] = {"mesh.shape=delta", "mesh.dilatation=point",
                               "material.state_density=point"};
  load_ok(GOOD "minimal.conf", delta_point, 3, &c);
  ck_assert_double_eq(c.time.cfl, 0.5);
  const char *delta_cfl[] = {"mesh.shape=delta", "time.cfl=0.4"};
  load_ok(GOOD "minimal.conf", delta_cfl, 2, &c);
  ck_assert_double_eq(c.time.cfl, 0.4);
}
END_TEST

/* Gravity as an incline: (g sin a, -g cos a); the resolved input keeps the
 * angle form and reads back to the same vector. stop.t_min defaults to the
 * end of the gravity ramp. */
START_TEST(t_gravity_angle)
{
  mpm_config c, back;
  const char *sets[] = {"gravity.angle=30", "gravity.g=10", "gravity.t_ramp=0.25",
                        "stop.ke=1e-10"};
  load_ok(GOOD "minimal.conf", sets, 4, &c);
  ck_assert_int_eq(c.gravity.use_angle, 1);
  ck_assert_double_eq_tol(c.gravity.gx, 5.0, 1e-14);              /* 10 sin 30 deg */
  ck_assert_double_eq_tol(c.gravity.gy, -5.0 * sqrt(3.0), 1e-14); /* -10 cos 30 deg */
  ck_assert_double_eq(c.stop.t_min, 0.25);
  char *text = written(&c);
  ck_assert_ptr_nonnull(strstr(text, "angle = 30"));
  ck_assert_ptr_null(strstr(text, "gx ="));
  write_bytes(CASE, text, strlen(text));
  load_ok(CASE, NULL, 0, &back);
  ck_assert_double_eq(back.gravity.gx, c.gravity.gx);
  ck_assert_double_eq(back.gravity.gy, c.gravity.gy);
  ck_assert_double_eq(back.stop.t_min, 0.25);
  free(text);
  /* the vector form leaves the angle keys out */
  load_ok(GOOD "minimal.conf", NULL, 0, &c);
  ck_assert_int_eq(c.gravity.use_angle, 0);
  text = written(&c);
  ck_assert_ptr_null(strstr(text, "angle ="));
  free(text);
}
END_TEST

/* full.conf sets every key to a value other than its default. */
START_TEST(t_every_key)
{
  mpm_config c;
  load_ok(GOOD "full.conf", NULL, 0, &c);
  ck_assert_int_eq(c.mesh.nx, 20);
  ck_assert_int_eq(c.mesh.ny, 12);
  ck_assert_double_eq(c.mesh.x0, -0.5);
  ck_assert_double_eq(c.mesh.y0, 0.25);
  ck_assert_double_eq(c.mesh.dx, 0.05);
  ck_assert_double_eq(c.mesh.dy, 0.1);
  ck_assert_str_eq(c.mesh.topology, "t3");
  ck_assert_str_eq(c.mesh.diagonal, "mirror");
  ck_assert_double_eq(c.mesh.mirror_x, 0.1);
  ck_assert_str_eq(c.mesh.shape, "delta");
  ck_assert_double_eq(c.time.dt, 1e-5);
  ck_assert_double_eq(c.time.cfl, 0.25);
  ck_assert_double_eq(c.time.t_end, 2);
  ck_assert_double_eq(c.time.frame_dt, 0.05);
  ck_assert_double_eq(c.time.flip, 0.99);
  ck_assert_double_eq(c.gravity.gx, 1.5);
  ck_assert_double_eq(c.gravity.gy, -9.81);
  ck_assert_double_eq(c.gravity.t_ramp, 0);
  ck_assert_str_eq(c.material.model, "elastic");
  ck_assert_double_eq(c.material.E, 2e7);
  ck_assert_double_eq(c.material.nu, 0.25);
  ck_assert_double_eq(c.material.rho_s, 2600);
  ck_assert_double_eq(c.material.rho_c, 1550);
  ck_assert_double_eq(c.material.mu_s, 0.4);
  ck_assert_double_eq(c.material.mu_2, 0.9);
  ck_assert_double_eq(c.material.I0, 0.3);
  ck_assert_double_eq(c.material.d, 0.001);
  ck_assert_double_eq(c.material.A, 0.5);
  ck_assert_double_eq(c.material.t0, 0.002);
  ck_assert_int_eq(c.bc.left, MPM_BC_NOSLIP);
  ck_assert_int_eq(c.bc.right, MPM_BC_FRICTIONLESS);
  ck_assert_int_eq(c.bc.bottom, MPM_BC_PERIODIC);
  ck_assert_int_eq(c.bc.top, MPM_BC_PERIODIC);
  ck_assert_int_eq(c.gravity.use_angle, 0);
  ck_assert_double_eq(c.stop.ke, 1e-8);
  ck_assert_double_eq(c.stop.t_min, 0.5);
  ck_assert_str_eq(c.output.dir, "full-run");
  ck_assert_int_eq(c.nfill, 3);

  const mpm_fill_config *r = &c.fill[0], *d = &c.fill[1], *p = &c.fill[2];
  ck_assert_str_eq(r->name, "block");
  ck_assert_int_eq(r->shape, MPM_FILL_RECTANGLE);
  ck_assert_double_eq(r->xmin, -0.5);
  ck_assert_double_eq(r->ymin, 0.25);
  ck_assert_double_eq(r->xmax, 0);
  ck_assert_double_eq(r->ymax, 0.75);
  ck_assert_int_eq(r->ppu, 3);
  ck_assert_double_eq(r->density, 1400);
  ck_assert_double_eq(r->vx, 0.5);
  ck_assert_double_eq(r->vy, -0.25);
  ck_assert_int_eq(r->lithostatic, 1);
  ck_assert_int_eq(r->nvert, 0);

  ck_assert_str_eq(d->name, "slug");
  ck_assert_int_eq(d->shape, MPM_FILL_DISC);
  ck_assert_double_eq(d->cx, 0.1);
  ck_assert_double_eq(d->cy, 0.8);
  ck_assert_double_eq(d->radius, 0.1);
  ck_assert_int_eq(d->ppu, 4);
  ck_assert_double_eq(d->density, 1200);
  ck_assert_double_eq(d->vx, 1.2);
  ck_assert_double_eq(d->vy, 3);
  ck_assert_int_eq(d->lithostatic, 0);

  ck_assert_str_eq(p->name, "wedge");
  ck_assert_int_eq(p->shape, MPM_FILL_POLYGON);
  ck_assert_int_eq(p->nvert, 3);
  const double px[] = {0.2, 0.5, 0.5}, py[] = {0.25, 0.25, 0.6};
  for (int i = 0; i < 3; i++) {
    ck_assert_double_eq(p->px[i], px[i]);
    ck_assert_double_eq(p->py[i], py[i]);
  }
  ck_assert_double_eq(p->px[3], 0);
  ck_assert_int_eq(p->ppu, 1);
  ck_assert_double_eq(p->density, 1550);  /* rho_c of this file */

  /* the bodies: a disc with every plane key, a box and a polygon */
  ck_assert_int_eq(c.nbody, 3);
  const mpm_body_config *w = &c.body[0], *b = &c.body[1], *g = &c.body[2];
  ck_assert_str_eq(w->name, "wheel");
  ck_assert_int_eq(w->shape, MPM_BODY_DISC);
  ck_assert_int_eq(w->axis, 2);  /* a plane body lies along z */
  ck_assert_double_eq(w->cx, 0.1);
  ck_assert_double_eq(w->cy, 0.8);
  ck_assert_double_eq(w->cz, 0);
  ck_assert_double_eq(w->radius, 0.15);
  ck_assert_double_eq(w->angle, 15);
  ck_assert_double_eq(w->length, 0);
  ck_assert_int_eq(w->side, MPM_BODY_INSIDE);
  ck_assert_int_eq(w->contact, MPM_CONTACT_FRICTION);
  ck_assert_double_eq(w->friction, 0.3);
  ck_assert_int_eq(w->ntable, 3);
  const double t[] = {0, 0.5, 1.5}, vx[] = {0, 0.1, 0.25}, om[] = {1, 2, -3};
  for (int i = 0; i < 3; i++) {
    ck_assert_double_eq(w->t[i], t[i]);
    ck_assert_double_eq(w->val[MPM_BODY_VX][i], vx[i]);
    ck_assert_double_eq(w->val[MPM_BODY_OMEGA][i], om[i]);
  }
  ck_assert_double_eq(w->t[3], 0);
  const int nval[MPM_BODY_NDOF] = {3, 1, 1, 3};
  for (int k = 0; k < MPM_BODY_NDOF; k++)
    ck_assert_int_eq(w->nval[k], nval[k]);
  ck_assert_double_eq(w->val[MPM_BODY_VY][0], 0.5);
  ck_assert_double_eq(w->val[MPM_BODY_VZ][0], 0);  /* not given: the one value 0 */
  ck_assert_int_eq(w->free[MPM_BODY_VX], 1);
  ck_assert_int_eq(w->free[MPM_BODY_VY], 1);
  ck_assert_int_eq(w->free[MPM_BODY_VZ], 0);
  ck_assert_int_eq(w->free[MPM_BODY_OMEGA], 1);
  ck_assert_double_eq(w->mass, 2.5);
  ck_assert_double_eq(w->inertia, 0.0125);
  ck_assert_double_eq(w->force[0], 1.5);
  ck_assert_double_eq(w->force[1], -2);
  ck_assert_double_eq(w->force[2], 0);
  ck_assert_double_eq(w->torque, 0.25);
  ck_assert_double_eq(w->damping, 0.5);
  ck_assert_int_eq(w->carve, 1);
  ck_assert_int_eq(w->nvert, 0);

  ck_assert_str_eq(b->name, "blade");
  ck_assert_int_eq(b->shape, MPM_BODY_BOX);
  ck_assert_double_eq(b->cx, -0.2);
  ck_assert_double_eq(b->cy, 1.2);
  ck_assert_double_eq(b->hx, 0.02);
  ck_assert_double_eq(b->hy, 0.15);
  ck_assert_double_eq(b->radius, 0);
  ck_assert_double_eq(b->angle, -30);
  ck_assert_int_eq(b->contact, MPM_CONTACT_FRICTIONLESS);
  ck_assert_int_eq(b->ntable, 0);
  for (int k = 0; k < MPM_BODY_NDOF; k++) {
    ck_assert_int_eq(b->nval[k], 1);
    ck_assert_double_eq(b->val[k][0], 0);
    ck_assert_int_eq(b->free[k], 0);
  }

  ck_assert_str_eq(g->name, "plough");
  ck_assert_int_eq(g->shape, MPM_BODY_POLYGON);
  ck_assert_int_eq(g->nvert, 3);
  const double gx[] = {0, 0.1, 0}, gy[] = {0, 0, 0.2};
  for (int i = 0; i < 3; i++) {
    ck_assert_double_eq(g->px[i], gx[i]);
    ck_assert_double_eq(g->py[i], gy[i]);
  }
  ck_assert_int_eq(g->nval[MPM_BODY_VX], 1);
  ck_assert_double_eq(g->val[MPM_BODY_VX][0], -0.5);
  ck_assert_int_eq(g->side, MPM_BODY_OUTSIDE);
  ck_assert_int_eq(g->carve, 0);
}
END_TEST

/* Comments of every kind (also inside lists), bare and single-quoted values,
 * repeated keys and sections. */
START_TEST(t_syntax)
{
  mpm_config c;
  load_ok(GOOD "syntax.conf", NULL, 0, &c);
  ck_assert_int_eq(c.mesh.nx, 6);  /* the last value counts */
  ck_assert_int_eq(c.mesh.ny, 4);  /* the two mesh sections merge */
  ck_assert_str_eq(c.mesh.topology, "t3");
  ck_assert_str_eq(c.mesh.diagonal, "\\");
  ck_assert_str_eq(c.fill[0].name, "tri-1");
  ck_assert_int_eq(c.fill[0].nvert, 3);
  ck_assert_double_eq(c.fill[0].px[1], 2.5);
  ck_assert_int_eq(c.fill[0].lithostatic, 1);
  ck_assert_str_eq(c.output.dir, "out dir");

  /* line numbers after comments are the file's lines */
  expect_error("# one\n// two\n/* three\n four */\n" BASE "mesh {\n  nx = 0\n}\n", NULL,
               CASE ":21: key 'mesh.nx': value 0 out of range (allowed: 1 ... 100000)");
  /* a comment inside a list, and a list over several lines */
  expect_error(BASE "fill p {\n  shape = polygon\n  x = {0, # first\n 1,\n 1}\n"
               "  y = {0, 0,\n bad}\n}\n", NULL,
               CASE ":22: key 'fill.p.y': expected a number, got 'bad'");
  /* ${NAME:-fallback} of libconfuse */
  mpm_config e;
  mpm_err err = {0};
  ck_assert_int_eq(load_text(BASE "output { dir = \"${GRANMPM_TEST_UNSET_VARIABLE:-x}/y\" }\n",
                             NULL, 0, &e, &err), MPM_OK);
  ck_assert_str_eq(e.output.dir, "x/y");
}
END_TEST

/* ---------------------------------------------------------------- overrides */

START_TEST(t_overrides)
{
  const char *sets[] = {
    "mesh.nx=12",
    " mesh.ny = 14 ",                 /* blanks around key and value */
    "mesh.topology=\"t3\"",           /* one pair of quotes is dropped */
    "mesh.diagonal='\\'",
    "time.t_end=2",
    "time.t_end=3",                   /* in order: the last counts */
    "material.model=elastic",
    "boundary.left=periodic",
    "boundary.right=periodic",
    "fill.ppu=3",                     /* every fill */
    "fill.pile.vx=-1.5",              /* one fill */
    "fill.lithostatic=yes",
    "gravity.t_ramp=0",               /* a pre-stressed fill needs full gravity at once */
    "output.dir=a b/c",
  };
  mpm_config c;
  load_ok(GOOD "minimal.conf", sets, (int)(sizeof sets / sizeof sets[0]), &c);
  ck_assert_int_eq(c.mesh.nx, 12);
  ck_assert_int_eq(c.mesh.ny, 14);
  ck_assert_str_eq(c.mesh.topology, "t3");
  ck_assert_str_eq(c.mesh.diagonal, "\\");
  ck_assert_double_eq(c.time.t_end, 3);
  ck_assert_str_eq(c.material.model, "elastic");
  ck_assert_int_eq(c.bc.left, MPM_BC_PERIODIC);
  ck_assert_int_eq(c.bc.right, MPM_BC_PERIODIC);
  ck_assert_int_eq(c.fill[0].ppu, 3);
  ck_assert_double_eq(c.fill[0].vx, -1.5);
  ck_assert_int_eq(c.fill[0].lithostatic, 1);
  ck_assert_str_eq(c.output.dir, "a b/c");

  /* lists, with and without braces; a shorter list clears the rest */
  const char *poly[] = {"fill.wedge.x={0.1, 0.2, 0.4, 0.3}", "fill.wedge.y=0.3,0.3,0.5,0.6",
                        "fill.wedge.x={0.1, 0.2, 0.3}", "fill.wedge.y={0.3, 0.3, 0.5}"};
  load_ok(GOOD "full.conf", poly, 2, &c);
  ck_assert_int_eq(c.fill[2].nvert, 4);
  ck_assert_double_eq(c.fill[2].px[3], 0.3);
  ck_assert_double_eq(c.fill[2].py[3], 0.6);
  load_ok(GOOD "full.conf", poly, 4, &c);
  ck_assert_int_eq(c.fill[2].nvert, 3);
  ck_assert_double_eq(c.fill[2].px[3], 0.0);
  ck_assert_double_eq(c.fill[2].py[3], 0.0);
  /* a density given with --set is not replaced by rho_c */
  const char *dens[] = {"fill.pile.density=1000"};
  load_ok(GOOD "minimal.conf", dens, 1, &c);
  ck_assert_double_eq(c.fill[0].density, 1000);
}
END_TEST

typedef struct bad_set {
  const char *set;
  const char *msg;
} bad_set;

static const bad_set bad_sets[] = {
  {"mesh.nx=abc", "--set 'mesh.nx=abc': key 'mesh.nx': expected an integer, got 'abc'"},
  {"mesh.nx=0", "--set 'mesh.nx=0': key 'mesh.nx': value 0 out of range (allowed: 1 ... 100000)"},
  {"time.dt=nan", "--set 'time.dt=nan': key 'time.dt': value nan out of range (allowed: 0, or 1e-12 ... 1e6 s)"},
  {"mesh.nx", "--set 'mesh.nx': expected section.key=value"},
  {"nx=3", "--set 'nx=3': 'nx' is not section.key (allowed sections: mesh, time, gravity, "
           "material, boundary, fill, body, stop, output, outlet, wall, remove, region, "
           "absorb)"},
  {"meshes.nx=3", "--set 'meshes.nx=3': unknown section 'meshes' (allowed: mesh, time, gravity, "
                  "material, boundary, fill, body, stop, output, outlet, wall, remove, region, "
                  "absorb)"},
  {"mesh.nxx=3", "--set 'mesh.nxx=3': unknown key 'mesh.nxx' (allowed keys in 'mesh': nx, ny, "
                 "x0, y0, dx, dy, nz, z0, dz, topology, diagonal, mirror_x, shape, "
                 "dilatation)"},
  {"fill.b.ppu=3", "--set 'fill.b.ppu=3': no fill titled 'b' (allowed: a)"},
  {"fill.a.speed=3", "--set 'fill.a.speed=3': unknown key 'fill.a.speed' (allowed keys in 'fill': "
                     "shape, xmin, ymin, xmax, ymax, cx, cy, radius, x, y, ppu, density, vx, vy, "
                     "zmin, zmax, axis, cz, vz, lithostatic, k0, pressure)"},
  {"fill.ppu=0", "--set 'fill.ppu=0': key 'fill.ppu': value 0 out of range (allowed: 1 ... 8)"},
  {"fill.a.radius=1", "--set 'fill.a.radius=1': key 'fill.a.radius': not used by shape "
                      "\"rectangle\" (allowed keys for \"rectangle\": xmin, ymin, xmax, ymax)"},
  {"fill.a.shape=disc", CASE ":11: key 'fill.a.xmin': not used by shape \"disc\" (allowed keys "
                        "for \"disc\": cx, cy, radius)"},
  {"fill.a.xmax=2", "--set 'fill.a.xmax=2': key 'fill.a.xmax': the fill spans x 0 ... 2, outside "
                    "the mesh (allowed: 0 ... 1 m)"},
  {"material.rho_s=1000", "--set 'material.rho_s=1000': key 'material.rho_s': rho_c = 1500 > "
                          "rho_s = 1000 (allowed: rho_c <= rho_s)"},
  {"boundary.top=periodic", "--set 'boundary.top=periodic': key 'boundary.top': bottom = "
                            "\"free\" but top = \"periodic\" (allowed: bottom and top both "
                            "\"periodic\" or neither)"},
  {"output.dir=", "--set 'output.dir=': key 'output.dir': 0 characters (allowed: a path of "
                  "1 ... 1023 characters)"},
  {"mesh.nx=1\n2", "--set 'mesh.nx=1?2': key 'mesh.nx': expected an integer, got '1?2'"},
};

START_TEST(t_bad_override)
{
  expect_error(BASE, bad_sets[_i].set, bad_sets[_i].msg);
}
END_TEST

/* A list longer than a polygon holds, given with --set (the argument is cut
 * in the message), and a fill title asked for when the file has no fill. */
START_TEST(t_bad_override_list)
{
  char set[400] = "fill.a.x={0";
  for (int i = 1; i <= 64; i++)
    snprintf(set + strlen(set), sizeof set - strlen(set), ",%d", i % 10);
  strcat(set, "}");
  expect_error(BASE, set, "--set 'fill.a.x={0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,"
                          "...': key 'fill.a.x': more than 64 values (allowed: 3 ... 64 "
                          "vertices)");
  expect_error("mesh {\n  nx = 1\n}\n", "fill.b.ppu=3",
               "--set 'fill.b.ppu=3': no fill titled 'b' (allowed: the file has no fill "
               "section)");
}
END_TEST

/* outlet.ends = "fixed" keeps the nodes at from and to held: an outlet of
 * one unit then frees no node, which the input refuses; two units free one.
 * An end on a symmetry edge is freed (a half silo's centre), so one unit
 * from the symmetry line is accepted, and refused beside a frictionless
 * wall. */
START_TEST(t_outlet_ends)
{
  const char *text = BASE "outlet {\n  edge = bottom\n  from = 0.2\n  to = 0.4\n"
                          "  ends = fixed\n}\n";
  mpm_config cfg;
  mpm_err err = {0};
  ck_assert_int_eq(load_text(text, NULL, 0, &cfg, &err), MPM_OK);
  ck_assert_int_eq(cfg.outlet.ends, MPM_OUTLET_ENDS_FIXED);
  expect_error(text, "outlet.to=0.3",
               "--set 'outlet.to=0.3': key 'outlet.to': \"fixed\" leaves no node free between "
               "the held ends at 0.2 and 0.3 m (allowed: a node strictly between from and to, "
               "or ends = \"free\")");
  const char *half = BASE "boundary {\n  left = symmetry\n}\n"
                          "outlet {\n  edge = bottom\n  from = 0\n  to = 0.1\n  ends = fixed\n}\n";
  ck_assert_int_eq(load_text(half, NULL, 0, &cfg, &err), MPM_OK);
  expect_error(half, "boundary.left=frictionless",
               "test_input.tmp/case.conf:23: key 'outlet.ends': \"fixed\" leaves no node "
               "free between the held ends at 0 and 0.1 m (allowed: a node strictly between "
               "from and to, or ends = \"free\")");
}
END_TEST

/* ------------------------------------------------------------- round trips */

START_TEST(t_round_trip_files)
{
  const char *files[] = {GOOD "minimal.conf", GOOD "full.conf", GOOD "syntax.conf",
                         GOOD "cylinders.conf", GOOD "bodies3d.conf",
                         TEST_SRCDIR "/inputs/V1-elastic-column.conf"};
  for (size_t i = 0; i < sizeof files / sizeof files[0]; i++)
    if (i < 5 || access(files[i], R_OK) == 0)
      round_trip(files[i], NULL, 0);
}
END_TEST

/* Values whose shortest text needs all 17 digits, tiny and huge magnitudes,
 * negative zero, names with a backslash and paths with quotes and '$'. */
START_TEST(t_round_trip_values)
{
  const char *sets[] = {
    "mesh.x0=-0.50000000000000011", "mesh.y0=0.24999999999999997", "mesh.dx=0.1",
    "mesh.mirror_x=-0.0", "mesh.diagonal=\\", "time.dt=2.5e-7",
    "time.cfl=0.3333333333333333", "gravity.gx=-0", "gravity.gy=-1e-300",
    "material.E=123456789.123",
    "material.nu=-0.99999999999999989", "fill.vx=1e-310", "fill.vy=9999.999999999998",
    "output.dir=it's a \"dir\" with ${HOME} and \\ in it",
    "body.wheel.angle=-0.0", "body.wheel.t={0, 1e-300, 0.30000000000000004}",
    "body.wheel.omega={1e-310, -9999.999999999998, 0.1}", "body.plough.x={-1e-9, 0.1, 0}",
  };
  round_trip(GOOD "full.conf", sets, (int)(sizeof sets / sizeof sets[0]));
  mpm_config c;
  load_ok(GOOD "full.conf", sets, (int)(sizeof sets / sizeof sets[0]), &c);
  ck_assert_str_eq(c.output.dir, "it's a \"dir\" with ${HOME} and \\ in it");
  ck_assert(signbit(c.gravity.gx));
}
END_TEST

/* 3D cylinders (cylinders.conf): a disc without fill.axis lies along z, as
 * before the key existed; along x its circle is (cy, cz) and it spans xmin
 * ... xmax, along y (cx, cz) and ymin ... ymax. The keys a cylinder does not
 * use keep their defaults and are left out of the resolved input. */
START_TEST(t_cylinders)
{
  mpm_config c;
  load_ok(GOOD "cylinders.conf", NULL, 0, &c);
  ck_assert_int_eq(c.mesh.nz, 6);
  ck_assert_int_eq(c.nfill, 3);
  const mpm_fill_config *z = &c.fill[0], *x = &c.fill[1], *y = &c.fill[2];
  ck_assert_str_eq(z->name, "post");
  ck_assert_int_eq(z->shape, MPM_FILL_DISC);
  ck_assert_int_eq(z->axis, 2);
  ck_assert_double_eq(z->cx, 0.15);
  ck_assert_double_eq(z->cy, 0.15);
  ck_assert_double_eq(z->radius, 0.1);
  ck_assert_double_eq(z->zmin, 0.05);
  ck_assert_double_eq(z->zmax, 0.55);
  ck_assert_double_eq(z->cz, 0);
  ck_assert_str_eq(x->name, "log");
  ck_assert_int_eq(x->shape, MPM_FILL_DISC);
  ck_assert_int_eq(x->axis, 0);
  ck_assert_double_eq(x->xmin, 0.3);
  ck_assert_double_eq(x->xmax, 0.75);
  ck_assert_double_eq(x->cy, 0.15);
  ck_assert_double_eq(x->cz, 0.2);
  ck_assert_double_eq(x->radius, 0.12);
  ck_assert_double_eq(x->cx, 0);
  ck_assert_double_eq(x->zmin, 0);
  ck_assert_double_eq(x->zmax, 0);
  ck_assert_str_eq(y->name, "pillar");
  ck_assert_int_eq(y->axis, 1);
  ck_assert_double_eq(y->ymin, 0.3);
  ck_assert_double_eq(y->ymax, 0.55);
  ck_assert_double_eq(y->cx, 0.5);
  ck_assert_double_eq(y->cz, 0.4);
  ck_assert_double_eq(y->radius, 0.15);
  ck_assert_double_eq(y->cy, 0);
  ck_assert_int_eq(y->ppu, 3);

  char *text = written(&c);
  const char *const has[3][3] = {{"  axis = \"z\"\n", "  zmin = 0.05\n", "  cx = 0.15\n"},
                                 {"  axis = \"x\"\n", "  cz = 0.2\n", "  xmax = 0.75\n"},
                                 {"  axis = \"y\"\n", "  cz = 0.4\n", "  ymin = 0.3\n"}};
  const char *const lacks[3][4] = {{"\n  cz =", "\n  xmin =", "\n  ymin =", "\n  x ="},
                                   {"\n  cx =", "\n  zmin =", "\n  zmax =", "\n  ymin ="},
                                   {"\n  cy =", "\n  zmin =", "\n  xmin =", "\n  xmax ="}};
  for (int i = 0; i < 3; i++) {
    char *f = item_text(text, "fill", c.fill[i].name);
    for (int k = 0; k < 3; k++)
      ck_assert_msg(strstr(f, has[i][k]), "fill %s without '%s':\n%s", c.fill[i].name,
                    has[i][k], f);
    for (int k = 0; k < 4; k++)
      ck_assert_msg(!strstr(f, lacks[i][k]), "fill %s with '%s':\n%s", c.fill[i].name,
                    lacks[i][k], f);
    free(f);
  }
  free(text);

  /* a plane disc has no axis: none written */
  load_ok(GOOD "full.conf", NULL, 0, &c);
  text = written(&c);
  ck_assert_ptr_null(strstr(text, "axis ="));
  ck_assert_ptr_null(strstr(text, "cz ="));
  free(text);

  /* turned along y with --set, the log's x span is refused where it was set */
  expect_error("mesh {\n  nx = 4\n  ny = 4\n  nz = 4\n  dx = 0.1\n  dy = 0.1\n  dz = 0.1\n}\n"
               "time {\n  t_end = 1\n}\n"
               "fill log {\n  shape = disc\n  axis = x\n  xmin = 0\n  xmax = 0.4\n"
               "  cy = 0.2\n  cz = 0.2\n  radius = 0.1\n}\n", "fill.log.axis=y",
               CASE ":15: key 'fill.log.xmin': not used by shape \"disc\" with axis \"y\" "
               "(allowed keys for \"disc\" with axis \"y\": ymin, ymax, cx, radius, axis, cz)");
}
END_TEST

START_TEST(t_write_fails)
{
  mpm_config c;
  mpm_io_input_defaults(&c);
  FILE *f = fopen("/dev/null", "r");  /* writes fail */
  ck_assert_ptr_nonnull(f);
  ck_assert_int_eq(mpm_io_input_write(f, &c), MPM_EIO);
  fclose(f);
  ck_assert_int_eq(mpm_io_input_write(NULL, &c), MPM_EINVAL);
}
END_TEST

/* ---------------------------------------------------------------- bad input */

/* The expected message of a bad input file: its "# expect: " line. */
static void expected_message(const char *path, char *msg, size_t cap)
{
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  char line[MPM_ERR_MSG + 64];
  msg[0] = '\0';
  while (fgets(line, sizeof line, f))
    if (strncmp(line, "# expect: ", 10) == 0) {
      line[strcspn(line, "\n")] = '\0';
      snprintf(msg, cap, "%s:%s", path, line + 10);
      break;
    }
  fclose(f);
  ck_assert_msg(msg[0], "%s has no '# expect: ' line", path);
}

/* 1 for a bad input that only check and run refuse, after the reader (the
 * fills, the time step, the size: "# stage: plan"). */
static int plan_stage(const char *path)
{
  FILE *f = fopen(path, "r");
  char line[256];
  int plan = 0;
  while (f && !plan && fgets(line, sizeof line, f))
    plan = strncmp(line, "# stage: plan", 13) == 0;
  if (f)
    fclose(f);
  return plan;
}

static int count_bad_files(void)
{
  glob_t g;
  int n = glob(BAD_GLOB, 0, NULL, &g) == 0 ? (int)g.gl_pathc : 0;
  globfree(&g);
  return n;
}

START_TEST(t_bad_file)
{
  glob_t g;
  ck_assert_int_eq(glob(BAD_GLOB, 0, NULL, &g), 0);
  ck_assert_uint_gt(g.gl_pathc, (size_t)_i);
  const char *path = g.gl_pathv[_i];
  char msg[MPM_ERR_MSG + 1200];
  expected_message(path, msg, sizeof msg);
  mpm_config c;
  mpm_err err = {0};
  int rc = mpm_io_input_load(path, NULL, 0, &c, &err);
  if (plan_stage(path)) {     /* a valid input whose run cannot be made: not the reader's */
    ck_assert_msg(rc == MPM_OK, "%s: status %d, message '%s'", path, rc, err.msg);
    globfree(&g);
    return;
  }
  ck_assert_msg(rc == MPM_EINPUT, "%s: status %d, message '%s'", path, rc, err.msg);
  ck_assert_int_eq(err.code, MPM_EINPUT);
  size_t n = strlen(msg);
  if (n > 3 && !strcmp(msg + n - 3, "..."))  /* a list other modules own: a prefix */
    ck_assert_msg(!strncmp(err.msg, msg, n - 3), "want '%s', got '%s'", msg, err.msg);
  else
    ck_assert_str_eq(err.msg, msg);
  ck_assert_ptr_null(strchr(err.msg, '\n'));
  /* on error the config is the defaults, not half a file */
  ck_assert_int_eq(c.nfill, 0);
  ck_assert_int_eq(c.mesh.nx, 0);
  globfree(&g);
}
END_TEST

START_TEST(t_bad_file_count)
{
  ck_assert_int_ge(count_bad_files(), 50);  /* the corpus is there */
}
END_TEST

/* Errors of the file itself, rather than of its content. */
START_TEST(t_file_errors)
{
  mpm_config c;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_io_input_load(TMP_DIR "/missing.conf", NULL, 0, &c, &err), MPM_EIO);
  ck_assert_str_eq(err.msg, TMP_DIR "/missing.conf: cannot open input file: No such file or directory");
  mkdir(TMP_DIR, 0777);
  ck_assert_int_eq(mpm_io_input_load(TMP_DIR, NULL, 0, &c, &err), MPM_EIO);
  ck_assert_str_eq(err.msg, TMP_DIR ": cannot read input file: Is a directory");
  write_bytes(CASE, "mesh {\n  nx = 1\0 }\n", 19);
  ck_assert_int_eq(mpm_io_input_load(CASE, NULL, 0, &c, &err), MPM_EINPUT);
  ck_assert_str_eq(err.msg, CASE ":2: NUL byte in the input file (allowed: text)");
  if (geteuid() != 0) {  /* root reads anything */
    write_bytes(CASE, BASE, strlen(BASE));
    ck_assert_int_eq(chmod(CASE, 0), 0);
    ck_assert_int_eq(mpm_io_input_load(CASE, NULL, 0, &c, &err), MPM_EIO);
    ck_assert_str_eq(err.msg, CASE ": cannot open input file: Permission denied");
    chmod(CASE, 0644);
  }
  /* one byte over the size limit (16 MiB of blanks): refused before parsing */
  size_t big = ((size_t)16 << 20) + 1;
  char *blanks = malloc(big);
  ck_assert_ptr_nonnull(blanks);
  memset(blanks, ' ', big);
  write_bytes(CASE, blanks, big);
  free(blanks);
  ck_assert_int_eq(mpm_io_input_load(CASE, NULL, 0, &c, &err), MPM_EINPUT);
  ck_assert_str_eq(err.msg, CASE ": input file larger than 16777216 bytes (allowed: at most "
                   "16777216)");
  /* a path with a newline still gives one line */
  ck_assert_int_eq(mpm_io_input_load(TMP_DIR "/a\nb.conf", NULL, 0, &c, &err), MPM_EIO);
  ck_assert_ptr_null(strchr(err.msg, '\n'));
}
END_TEST

START_TEST(t_bad_arguments)
{
  mpm_config c;
  mpm_err err = {0};
  const char *sets[] = {NULL};
  ck_assert_int_eq(mpm_io_input_load(NULL, NULL, 0, &c, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_io_input_load(GOOD "minimal.conf", NULL, -1, &c, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_io_input_load(GOOD "minimal.conf", NULL, 1, &c, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_io_input_load(GOOD "minimal.conf", sets, 1, &c, &err), MPM_EINVAL);
  ck_assert_str_eq(err.msg, "--set number 1 is missing");
  ck_assert_int_eq(mpm_io_input_load(GOOD "minimal.conf", NULL, 0, NULL, &err), MPM_EINVAL);
  ck_assert_str_eq(err.msg, "mpm_io_input_load: invalid arguments");
  ck_assert_int_eq(mpm_io_input_load(GOOD "minimal.conf", NULL, 0, &c, NULL), MPM_OK);
  ck_assert_int_eq(mpm_io_input_load(TMP_DIR "/missing.conf", NULL, 0, &c, NULL), MPM_EIO);
}
END_TEST

/* Keys left at a default are reported where their section opens; a
 * conflict names the key set last, in the file or with --set. */
START_TEST(t_error_lines)
{
  expect_error(BASE "material {\n  model = \"elastic\"\n  mu_2 = 0.2\n}\n", NULL,
               CASE ":18: key 'material.mu_2': mu_s = 0.3819 >= mu_2 = 0.2 (allowed: mu_s < mu_2)");
  expect_error(BASE "material {\n  mu_2 = 0.2\n  mu_s = 0.1\n  mu_s = 0.3\n}\n", NULL,
               CASE ":19: key 'material.mu_s': mu_s = 0.3 >= mu_2 = 0.2 (allowed: mu_s < mu_2)");
  expect_error("time {\n  t_end = 1\n}\n\nmesh {\n  nx = 1\n  ny = 1\n  dx = 1\n}\n", NULL,
               CASE ":5: key 'mesh.dy': required, not set (allowed: 1e-6 ... 1e6 m)");
  expect_error(BASE "fill b {\n  shape = disc\n  cx = 0.5\n}\n", NULL,
               CASE ":16: key 'fill.b.cy': required for shape \"disc\", not set (allowed: "
               "-1e9 ... 1e9 m)");
  expect_error(BASE, "time.frame_dt=5",
               "--set 'time.frame_dt=5': key 'time.frame_dt': frame_dt = 5 > t_end = 1 "
               "(allowed: frame_dt <= t_end)");
}
END_TEST

/* ------------------------------------------------------------ the reference */

typedef struct doc_row {
  char key[64], type[32], unit[32], def[64], allowed[256];
} doc_row;

/* Copy a table cell without backticks and surrounding blanks. */
static void cell(const char *from, size_t n, char *to, size_t cap)
{
  size_t k = 0;
  for (size_t i = 0; i < n && k + 1 < cap; i++)
    if (from[i] != '`')
      to[k++] = from[i];
  to[k] = '\0';
  while (k > 0 && to[k - 1] == ' ')
    to[--k] = '\0';
  memmove(to, to + strspn(to, " "), strlen(to + strspn(to, " ")) + 1);
}

static int parse_row(const char *line, doc_row *r)
{
  if (strncmp(line, "| `", 3) != 0)
    return 0;
  char *dst[] = {r->key, r->type, r->unit, r->def, r->allowed};
  size_t cap[] = {sizeof r->key, sizeof r->type, sizeof r->unit, sizeof r->def,
                  sizeof r->allowed};
  const char *p = line + 1;
  for (int i = 0; i < 5; i++) {
    const char *bar = strchr(p, '|');
    ck_assert_ptr_nonnull(bar);
    cell(p, (size_t)(bar - p), dst[i], cap[i]);
    p = bar + 1;
  }
  return 1;
}

/* The fill of full.conf that uses a fill key. */
static const char *fill_for(const char *key)
{
  if (strstr("xmin ymin xmax ymax", key))
    return "block";
  if (strstr("cx cy radius", key))
    return "slug";
  if (!strcmp(key, "x") || !strcmp(key, "y"))
    return "wedge";
  return "block";
}

/* The body of full.conf that uses a body key. */
static const char *body_for(const char *key)
{
  if (!strcmp(key, "hx") || !strcmp(key, "hy"))
    return "blade";
  if (!strcmp(key, "x") || !strcmp(key, "y"))
    return "plough";
  return "wheel";
}

/* A value outside what the key allows, and the message body it gives. */
static void bad_value(const doc_row *r, char *val, size_t vcap, char *body, size_t bcap)
{
  char allowed[300];
  if (strcmp(r->unit, "-") != 0 && (!strcmp(r->type, "number") || !strcmp(r->type, "list")))
    snprintf(allowed, sizeof allowed, "%s %s", r->allowed, r->unit);
  else
    snprintf(allowed, sizeof allowed, "%s", r->allowed);
  if (!strcmp(r->type, "integer") || !strcmp(r->type, "number") || !strcmp(r->type, "list")) {
    snprintf(val, vcap, "%s", !strcmp(r->type, "integer") ? "999999999999" : "1e300");
    snprintf(body, bcap, "value %s out of range (allowed: %s)", val, allowed);
  } else if (!strcmp(r->type, "name")) {
    snprintf(val, vcap, "zzz");
    snprintf(body, bcap, "unknown value 'zzz' (allowed: %s)", allowed);
  } else if (!strcmp(r->type, "boolean")) {
    snprintf(val, vcap, "zzz");
    snprintf(body, bcap, "expected true or false, got 'zzz' (allowed: %s)", allowed);
  } else {
    ck_assert_str_eq(r->type, "path");
    memset(val, 'd', 1100);
    val[1100] = '\0';
    snprintf(body, bcap, "1100 characters (allowed: %s)", allowed);
  }
}

/* Each documented key exists and allows what the reference says. */
static void check_doc_allowed(const doc_row *r)
{
  char key[96], set[1300], val[1200], body[1600], named[120];
  const char *dot = strchr(r->key, '.');
  ck_assert_ptr_nonnull(dot);
  if (!strncmp(r->key, "fill.", 5))
    snprintf(key, sizeof key, "fill.%s.%s", fill_for(dot + 1), dot + 1);
  else if (!strncmp(r->key, "body.", 5))
    snprintf(key, sizeof key, "body.%s.%s", body_for(dot + 1), dot + 1);
  else
    snprintf(key, sizeof key, "%s", r->key);
  bad_value(r, val, sizeof val, body, sizeof body);
  snprintf(set, sizeof set, "%s=%s", key, val);
  const char *sets[] = {set};
  mpm_config c;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_io_input_load(GOOD "full.conf", sets, 1, &c, &err), MPM_EINPUT);
  snprintf(named, sizeof named, ": key '%s': ", key);
  ck_assert_msg(strstr(err.msg, named) && strstr(err.msg, body), "%s: the reference says '%s', "
                "the reader says '%s'", r->key, body, err.msg);
}

/* A value written by mpm_io_input_write for "  key = value" in a section. */
static int written_value(const char *text, const char *section, const char *key, char *out,
                         size_t cap)
{
  char head[64], pat[64];
  snprintf(head, sizeof head, "\n%s ", section);
  snprintf(pat, sizeof pat, "\n  %s = ", key);
  const char *s = strstr(text, head);
  const char *k = s ? strstr(s, pat) : NULL;
  if (!k)
    return 0;
  k += strlen(pat);
  size_t n = strcspn(k, "\n");
  snprintf(out, cap, "%.*s", (int)n, k);
  return 1;
}

/* The value of section.key ("gravity.angle") in a resolved input text. */
static int written_key(const char *text, const char *key, char *out, size_t cap)
{
  char section[32];
  const char *dot = strchr(key, '.');
  if (!dot || dot - key >= (long)sizeof section)
    return 0;
  snprintf(section, sizeof section, "%.*s", (int)(dot - key), key);
  return written_value(text, section, dot + 1, out, cap);
}

/* Documented defaults are what minimal.conf (only required keys) resolves to.
 * The resolved input leaves out the form of gravity that was not used, so
 * gravity.angle and gravity.g are read from polar_text (minimal.conf with
 * gravity given as an angle). A default written as another key's name
 * ("material.rho_c") is that key's resolved value. A body's defaults are
 * read from text_body, whose first body has only its required keys. */
static void check_doc_default(const doc_row *r, const char *text, const char *polar_text,
                              const char *text3, const char *text_cyl, const char *text_body)
{
  char value[128], other[128];
  if (!strncmp(r->def, "required", 8))
    return;
  /* mesh.nz = 0, the plane, is what its absence from a plane input means */
  if (!strcmp(r->key, "mesh.nz")) {
    ck_assert(!written_key(text, r->key, value, sizeof value) && !strcmp(r->def, "0"));
    return;
  }
  /* the keys of 3D runs are written only in a 3D input's resolved text, a
   * cylinder's axis only for a cylinder (the first of text_cyl has the
   * default), a body's only in an input with a body (text_body, 3D) */
  ck_assert_msg(written_key(text, r->key, value, sizeof value) ||
                written_key(polar_text, r->key, value, sizeof value) ||
                written_key(text3, r->key, value, sizeof value) ||
                written_key(text_cyl, r->key, value, sizeof value) ||
                written_key(text_body, r->key, value, sizeof value), "%s not written", r->key);
  const char *want = r->def;
  if (isalpha((unsigned char)want[0]) && strchr(want, '.') &&
      written_key(text, want, other, sizeof other))
    want = other;
  char *end;
  double factor = strtod(want, &end);                  /* "10 material.t0": a multiple */
  if (end != want && *end == ' ' && written_key(text, end + 1, other, sizeof other)) {
    double got = strtod(value, NULL), base = strtod(other, NULL);
    ck_assert_msg(fabs(got - factor * base) <= 1e-12 * fabs(factor * base),
                  "%s: the reference says default %s, the reader gives %s", r->key, r->def, value);
    return;
  }
  ck_assert_msg(!strcmp(value, want), "%s: the reference says default %s, the reader gives %s",
                r->key, r->def, value);
}

START_TEST(t_reference)
{
  FILE *f = fopen(DOCS, "r");
  ck_assert_msg(f != NULL, "cannot open %s", DOCS);
  mpm_config c;
  load_ok(GOOD "minimal.conf", NULL, 0, &c);
  char *min_text = written(&c);
  const char *polar[] = {"gravity.angle=0"};
  load_ok(GOOD "minimal.conf", polar, 1, &c);
  char *polar_text = written(&c);
  load_ok(GOOD "full.conf", NULL, 0, &c);
  char *full_text = written(&c);
  const char *box[] = {"mesh.nz=2", "mesh.dz=0.25", "fill.pile.zmin=0", "fill.pile.zmax=0.5"};
  load_ok(GOOD "minimal.conf", box, 4, &c);
  char *text3 = written(&c);
  load_ok(GOOD "cylinders.conf", NULL, 0, &c);
  char *text_cyl = written(&c);
  load_ok(GOOD "bodies3d.conf", NULL, 0, &c);
  char *text_body = written(&c);
  char line[1024], listed[4096] = " ";
  doc_row r;
  int rows = 0;
  while (fgets(line, sizeof line, f)) {
    if (!parse_row(line, &r))
      continue;
    rows++;
    check_doc_allowed(&r);
    check_doc_default(&r, min_text, polar_text, text3, text_cyl, text_body);
    strncat(listed, strchr(r.key, '.') + 1, sizeof listed - strlen(listed) - 2);
    strcat(listed, " ");
  }
  fclose(f);
  ck_assert_int_ge(rows, 130);
  /* every key the writer knows is documented, the 3D ones too */
  const char *texts[] = {full_text, text3, text_cyl, text_body};
  for (int k = 0; k < 4; k++)
    for (const char *p = texts[k]; (p = strstr(p, "\n  ")); p++) {
      char key[64], pat[70];
      sscanf(p + 3, "%63s", key);
      snprintf(pat, sizeof pat, " %s ", key);
      ck_assert_msg(strstr(listed, pat), "key '%s' is not in %s", key, DOCS);
    }
  free(text3);
  free(text_cyl);
  free(text_body);
  free(min_text);
  free(polar_text);
  free(full_text);
}
END_TEST

static Suite *input_suite(void)
{
  Suite *s = suite_create("input");
  TCase *tc = tcase_create("good");
  tcase_add_test(tc, t_defaults);
  tcase_add_test(tc, t_minimal);
  tcase_add_test(tc, t_every_key);
  tcase_add_test(tc, t_scheme_defaults);
  tcase_add_test(tc, t_gravity_angle);
  tcase_add_test(tc, t_syntax);
  tcase_add_test(tc, t_overrides);
  tcase_add_test(tc, t_round_trip_files);
  tcase_add_test(tc, t_round_trip_values);
  tcase_add_test(tc, t_cylinders);
  tcase_add_test(tc, t_write_fails);
  tcase_add_test(tc, t_reference);
  suite_add_tcase(s, tc);

  TCase *bad = tcase_create("bad");
  tcase_add_loop_test(bad, t_bad_file, 0, count_bad_files());
  tcase_add_test(bad, t_bad_file_count);
  tcase_add_loop_test(bad, t_bad_override, 0, (int)(sizeof bad_sets / sizeof bad_sets[0]));
  tcase_add_test(bad, t_bad_override_list);
  tcase_add_test(bad, t_outlet_ends);
  tcase_add_test(bad, t_file_errors);
  tcase_add_test(bad, t_bad_arguments);
  tcase_add_test(bad, t_error_lines);
  suite_add_tcase(s, bad);
  return s;
}

int main(void)
{
  SRunner *sr = srunner_create(input_suite());
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  remove(CASE);
  remove(TMP_DIR);
  return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
