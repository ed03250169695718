/* test_input_body.c: the body sections of the input reader (src/io/input*.c,
 * docs/input-reference.md, section body): a plane and a 3D body read back
 * key by key, the defaults, the --set forms, and every error of a body
 * named by its file, line and key body.TITLE.KEY. The write -> load round
 * trip of bodies and the reference page are tested by test_input.c. */
#define _POSIX_C_SOURCE 200809L
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/error.h"
#include "io/io.h"

#define TMP_DIR "test_input_body.tmp"
#include "input_case.h"

/* A body with only its required keys has the documented defaults. */
static void check_body_defaults(const mpm_body_config *b)
{
  ck_assert_int_eq(b->shape, MPM_BODY_DISC);
  ck_assert_int_eq(b->axis, 2);
  ck_assert_double_eq(b->cz, 0);
  ck_assert_double_eq(b->hx, 0);
  ck_assert_double_eq(b->hy, 0);
  ck_assert_int_eq(b->nvert, 0);
  ck_assert_double_eq(b->angle, 0);
  ck_assert_double_eq(b->length, 0);
  ck_assert_int_eq(b->side, MPM_BODY_OUTSIDE);
  ck_assert_int_eq(b->contact, MPM_CONTACT_NOSLIP);
  ck_assert_double_eq(b->friction, 0);
  ck_assert_int_eq(b->ntable, 0);
  for (int d = 0; d < MPM_BODY_NDOF; d++) {
    ck_assert_int_eq(b->nval[d], 1);  /* one value, 0: at rest */
    ck_assert_double_eq(b->val[d][0], 0);
    ck_assert_int_eq(b->free[d], 0);
  }
  ck_assert_double_eq(b->mass, 0);
  ck_assert_double_eq(b->inertia, 0);
  for (int a = 0; a < 3; a++)
    ck_assert_double_eq(b->force[a], 0);
  ck_assert_double_eq(b->torque, 0);
  ck_assert_double_eq(b->damping, 0);
  ck_assert_int_eq(b->carve, 0);
}

/* A plane input without a body has none; a plane disc with its required
 * keys only takes every default, and the resolved input writes the keys of
 * its shape and no key of 3D runs. */
START_TEST(t_body_defaults)
{
  mpm_config c;
  load_ok(GOOD "minimal.conf", NULL, 0, &c);
  ck_assert_int_eq(c.nbody, 0);
  mpm_err err = {0};
  ck_assert_int_eq(load_text(BASE DISC, NULL, 0, &c, &err), MPM_OK);
  ck_assert_int_eq(c.nbody, 1);
  ck_assert_str_eq(c.body[0].name, "w");
  ck_assert_double_eq(c.body[0].cx, 0.5);
  ck_assert_double_eq(c.body[0].cy, 0.7);
  ck_assert_double_eq(c.body[0].radius, 0.1);
  check_body_defaults(&c.body[0]);
  char *text = written(&c);
  char *b = item_text(text, "body", "w");
  const char *const has[] = {"  shape = \"disc\"\n", "  radius = 0.1\n", "  t = {}\n",
                             "  vx = {0}\n", "  omega = {0}\n", "  free_rotation = false\n",
                             "  side = \"outside\"\n", "  contact = \"noslip\"\n"};
  const char *const lacks[] = {"\n  hx =", "\n  x =", "\n  axis =", "\n  cz =", "\n  vz =",
                               "\n  free_z =", "\n  fz =", "\n  length ="};
  for (size_t k = 0; k < sizeof has / sizeof has[0]; k++)
    ck_assert_msg(strstr(b, has[k]), "body without '%s':\n%s", has[k], b);
  for (size_t k = 0; k < sizeof lacks / sizeof lacks[0]; k++)
    ck_assert_msg(!strstr(b, lacks[k]), "body with '%s':\n%s", lacks[k], b);
  free(b);
  free(text);
  /* a check made after the load names a body's key where it was set, or
   * where its section opens */
  mpm_io_input *in = NULL;
  ck_assert_int_eq(mpm_io_input_open_text(&in, "bodies.conf", BASE DISC, NULL, 0, &c, &err),
                   MPM_OK);
  ck_assert_int_eq(mpm_io_input_fail(in, &c, "body.w.radius", &err, "too small"), MPM_EINPUT);
  ck_assert_str_eq(err.msg, "bodies.conf:19: key 'body.w.radius': too small");
  ck_assert_int_eq(mpm_io_input_fail(in, &c, "body.w.mass", &err, "too light"), MPM_EINPUT);
  ck_assert_str_eq(err.msg, "bodies.conf:16: key 'body.w.mass': too light");
  mpm_io_input_free(in);
}
END_TEST

/* A 3D run (bodies3d.conf): the defaults of the 3D keys, every key of
 * "drum" read back, a polygon along z; each body written with the keys of
 * its shape only. */
START_TEST(t_bodies3)
{
  mpm_config c;
  load_ok(GOOD "bodies3d.conf", NULL, 0, &c);
  ck_assert_int_eq(c.nbody, 3);
  const mpm_body_config *p = &c.body[0], *d = &c.body[1], *q = &c.body[2];
  ck_assert_str_eq(p->name, "plain");
  ck_assert_double_eq(p->radius, 0.1);
  check_body_defaults(p);

  ck_assert_str_eq(d->name, "drum");
  ck_assert_int_eq(d->shape, MPM_BODY_BOX);
  ck_assert_int_eq(d->axis, 0);
  ck_assert_double_eq(d->cx, 0.35);
  ck_assert_double_eq(d->cy, 0.45);
  ck_assert_double_eq(d->cz, 0.05);
  ck_assert_double_eq(d->hx, 0.05);
  ck_assert_double_eq(d->hy, 0.1);
  ck_assert_double_eq(d->radius, 0);
  ck_assert_double_eq(d->angle, 90);
  ck_assert_double_eq(d->length, 0.3);
  ck_assert_int_eq(d->side, MPM_BODY_INSIDE);
  ck_assert_int_eq(d->contact, MPM_CONTACT_FRICTION);
  ck_assert_double_eq(d->friction, 0.5);
  ck_assert_int_eq(d->ntable, 2);
  ck_assert_double_eq(d->t[0], 0);
  ck_assert_double_eq(d->t[1], 0.25);
  const int nval[MPM_BODY_NDOF] = {1, 2, 2, 1};
  const double first[MPM_BODY_NDOF] = {0.1, 0, 0.2, 3};
  for (int k = 0; k < MPM_BODY_NDOF; k++) {
    ck_assert_int_eq(d->nval[k], nval[k]);
    ck_assert_double_eq(d->val[k][0], first[k]);
    ck_assert_int_eq(d->free[k], 1);
  }
  ck_assert_double_eq(d->val[MPM_BODY_VY][1], -0.2);
  ck_assert_double_eq(d->val[MPM_BODY_VZ][1], 0);
  ck_assert_double_eq(d->mass, 4);
  ck_assert_double_eq(d->inertia, 0.02);
  ck_assert_double_eq(d->force[0], 1);
  ck_assert_double_eq(d->force[1], -2);
  ck_assert_double_eq(d->force[2], -1);
  ck_assert_double_eq(d->torque, 0.5);
  ck_assert_double_eq(d->damping, 2);
  ck_assert_int_eq(d->carve, 1);

  ck_assert_str_eq(q->name, "prism");
  ck_assert_int_eq(q->shape, MPM_BODY_POLYGON);
  ck_assert_int_eq(q->axis, 2);
  ck_assert_int_eq(q->nvert, 3);
  ck_assert_double_eq(q->px[0], -0.05);
  ck_assert_double_eq(q->py[2], 0.08);

  char *text = written(&c);
  const char *const has[3][3] = {{"  radius = 0.1\n", "  axis = \"z\"\n", "  vz = {0}\n"},
                                 {"  hy = 0.1\n", "  axis = \"x\"\n", "  vz = {0.2, 0}\n"},
                                 {"  x = {-0.05, 0.05, 0}\n", "  length = 0\n", "  fz = 0\n"}};
  const char *const lacks[3][3] = {{"\n  hx =", "\n  x =", "\n  y ="},
                                   {"\n  radius =", "\n  x =", "\n  y ="},
                                   {"\n  radius =", "\n  hx =", "\n  hy ="}};
  for (int i = 0; i < 3; i++) {
    char *b = item_text(text, "body", c.body[i].name);
    for (int k = 0; k < 3; k++) {
      ck_assert_msg(strstr(b, has[i][k]), "body %s without '%s':\n%s", c.body[i].name,
                    has[i][k], b);
      ck_assert_msg(!strstr(b, lacks[i][k]), "body %s with '%s':\n%s", c.body[i].name,
                    lacks[i][k], b);
    }
    free(b);
  }
  free(text);
}
END_TEST

/* --set body.KEY in every body, body.TITLE.KEY in one, lists with or without
 * braces; a fill and a body may share a title. */
START_TEST(t_body_overrides)
{
  const char *sets[] = {
    "body.angle=45",           /* every body */
    "body.wheel.angle=10",     /* one body, after */
    "body.t={0, 1}",
    "body.blade.vx={0.5, -0.5}",
    "body.plough.omega=2, 4",  /* a list without braces */
    "body.wheel.vx=0.1",       /* one value: constant */
    "body.wheel.vy='0.2'",
    "body.wheel.omega={1}",
  };
  const char *text = BASE DISC "body a {\n  cx = 0.1\n  cy = 0.1\n  radius = 0.05\n}\n";
  mpm_config c;
  mpm_err err = {0};
  ck_assert_int_eq(load_text(text, NULL, 0, &c, &err), MPM_OK);  /* fill a and body a */
  ck_assert_str_eq(c.fill[0].name, "a");
  ck_assert_str_eq(c.body[1].name, "a");
  load_ok(GOOD "full.conf", sets, (int)(sizeof sets / sizeof sets[0]), &c);
  ck_assert_double_eq(c.body[0].angle, 10);
  ck_assert_double_eq(c.body[1].angle, 45);
  ck_assert_double_eq(c.body[2].angle, 45);
  for (int i = 0; i < 3; i++) {
    ck_assert_int_eq(c.body[i].ntable, 2);
    ck_assert_double_eq(c.body[i].t[1], 1);
  }
  ck_assert_int_eq(c.body[1].nval[MPM_BODY_VX], 2);
  ck_assert_double_eq(c.body[1].val[MPM_BODY_VX][1], -0.5);
  ck_assert_int_eq(c.body[2].nval[MPM_BODY_OMEGA], 2);
  ck_assert_double_eq(c.body[2].val[MPM_BODY_OMEGA][1], 4);
  ck_assert_int_eq(c.body[0].nval[MPM_BODY_VX], 1);
  ck_assert_double_eq(c.body[0].val[MPM_BODY_VX][0], 0.1);
  ck_assert_double_eq(c.body[0].val[MPM_BODY_VX][1], 0);  /* the shorter list clears the rest */
  ck_assert_double_eq(c.body[0].val[MPM_BODY_VY][0], 0.2);
  ck_assert_int_eq(c.body[0].nval[MPM_BODY_OMEGA], 1);
  /* a shape changed with --set refuses the keys of the old one, needs its own */
  expect_error(BASE DISC, "body.w.shape=box",
               CASE ":19: key 'body.w.radius': not used by shape \"box\" (allowed keys for "
               "\"box\": hx, hy)");
  expect_error(BASE "body w {\n  cx = 0.5\n  cy = 0.7\n}\n", "body.w.shape=box",
               CASE ":16: key 'body.w.hx': required for shape \"box\", not set (allowed: "
               "1e-6 ... 1e9 m)");
  const char *set_box[] = {"body.w.shape=box", "body.w.hx=0.1", "body.w.hy=0.2"};
  ck_assert_int_eq(load_text(BASE "body w {\n  cx = 0.5\n  cy = 0.7\n}\n", set_box, 3, &c, &err),
                   MPM_OK);
  ck_assert_int_eq(c.body[0].shape, MPM_BODY_BOX);
  ck_assert_double_eq(c.body[0].hy, 0.2);
  const char *more[] = {"body.blade.contact=frictionless", "body.blade.carve=on",
                        "body.wheel.contact=noslip", "body.wheel.friction=0"};
  load_ok(GOOD "full.conf", more, 4, &c);
  ck_assert_int_eq(c.body[1].carve, 1);
  ck_assert_int_eq(c.body[0].contact, MPM_CONTACT_NOSLIP);
  /* the forms of --set refused */
  expect_error(BASE DISC, "body.v.cx=0.1",
               "--set 'body.v.cx=0.1': no body titled 'v' (allowed: w)");
  expect_error(BASE, "body.w.cx=0.1",
               "--set 'body.w.cx=0.1': no body titled 'w' (allowed: the file has no body "
               "section)");
  expect_error(BASE DISC, "body.cx=5",
               "--set 'body.cx=5': key 'body.w.cx': cx = 5 lies outside the mesh (allowed: "
               "0 ... 1 m)");
  expect_error(BASE DISC, "body.w.vx={}",
               "--set 'body.w.vx={}': key 'body.w.vx': vx has 0 values, t has 0 (allowed: 1 "
               "value, or as many as t)");
  expect_error(BASE DISC, "body.w.t={0, 2, 1}",
               "--set 'body.w.t={0, 2, 1}': key 'body.w.t': value 1 is not larger than the one "
               "before it, 2 (allowed: strictly increasing values)");
  expect_error(BASE DISC, "body.speed=1",
               "--set 'body.speed=1': unknown key 'body.speed' (allowed keys in 'body': " BODY_KEYS
               ")");
}
END_TEST

typedef struct bad_body {
  const char *text;
  const char *msg;
} bad_body;

/* Each error of a body in a file: the file, the line, the key
 * body.TITLE.KEY and what is wrong. */
static const bad_body bad_bodies[] = {
  /* keys of the shape */
  {BASE DISC_OPEN "  hx = 0.1\n}\n",
   CASE ":20: key 'body.w.hx': not used by shape \"disc\" (allowed keys for \"disc\": radius)"},
  {BASE DISC_OPEN "  x = {0, 1, 0}\n}\n",
   CASE ":20: key 'body.w.x': not used by shape \"disc\" (allowed keys for \"disc\": radius)"},
  {BASE "body w {\n  cx = 0.5\n  cy = 0.7\n}\n",
   CASE ":16: key 'body.w.radius': required for shape \"disc\", not set (allowed: 1e-6 ... 1e9 "
   "m)"},
  {BASE "body w {\n  shape = box\n  cx = 0.5\n  cy = 0.7\n  hx = 0.1\n}\n",
   CASE ":16: key 'body.w.hy': required for shape \"box\", not set (allowed: 1e-6 ... 1e9 m)"},
  {BASE "body w {\n  shape = box\n  cx = 0.5\n  cy = 0.7\n  hx = 0.1\n  hy = 0.1\n"
   "  radius = 0.1\n}\n",
   CASE ":22: key 'body.w.radius': not used by shape \"box\" (allowed keys for \"box\": hx, hy)"},
  {BASE "body w {\n  shape = polygon\n  cx = 0.5\n  cy = 0.7\n  y = {0, 0, 0.1}\n}\n",
   CASE ":16: key 'body.w.x': required for shape \"polygon\", not set (allowed: -1e9 ... 1e9 m)"},
  {BASE "body w {\n  cy = 0.7\n  radius = 0.1\n}\n",
   CASE ":16: key 'body.w.cx': required, not set (allowed: -1e9 ... 1e9 m)"},
  {BASE "body w {\n  cx = 0.7\n  radius = 0.1\n}\n",
   CASE ":16: key 'body.w.cy': required, not set (allowed: -1e9 ... 1e9 m)"},
  {BASE DISC_OPEN "  shape = cube\n}\n",
   CASE ":20: key 'body.w.shape': unknown value 'cube' (allowed: \"disc\", \"box\", \"polygon\")"},
  /* sizes and the polygon */
  {BASE "body w {\n  cx = 0.5\n  cy = 0.7\n  radius = 0\n}\n",
   CASE ":19: key 'body.w.radius': value 0 out of range (allowed: 1e-6 ... 1e9 m)"},
  {BASE "body w {\n  shape = box\n  cx = 0.5\n  cy = 0.7\n  hx = 0.1\n  hy = -1\n}\n",
   CASE ":21: key 'body.w.hy': value -1 out of range (allowed: 1e-6 ... 1e9 m)"},
  {BASE POLY_OPEN "  x = {0, 0.1, 0}\n  y = {0, 0}\n}\n",
   CASE ":21: key 'body.w.y': x has 3 values, y has 2 (allowed: as many x values as y "
   "values)"},
  {BASE POLY_OPEN "  x = {0, 0.1}\n  y = {0, 0.1}\n}\n",
   CASE ":21: key 'body.w.y': 2 vertices (allowed: 3 ... 64 vertices)"},
  {BASE POLY_OPEN "  y = {0, 0.1, 0.2}\n  x = {0, 0.1, 0.2}\n}\n",
   CASE ":21: key 'body.w.x': the polygon encloses no area (allowed: 3 ... 64 vertices around "
   "a region)"},
  /* the centre in the mesh */
  {BASE "body w {\n  cx = 1.5\n  cy = 0.7\n  radius = 0.1\n}\n",
   CASE ":17: key 'body.w.cx': cx = 1.5 lies outside the mesh (allowed: 0 ... 1 m)"},
  {BASE "body w {\n  cx = 0.5\n  cy = -0.25\n  radius = 0.1\n}\n",
   CASE ":18: key 'body.w.cy': cy = -0.25 lies outside the mesh (allowed: 0 ... 1 m)"},
  /* the turn, the side, the contact */
  {BASE DISC_OPEN "  angle = 400\n}\n",
   CASE ":20: key 'body.w.angle': value 400 out of range (allowed: -360 ... 360 deg)"},
  {BASE DISC_OPEN "  side = left\n}\n",
   CASE ":20: key 'body.w.side': unknown value 'left' (allowed: \"outside\", \"inside\")"},
  {BASE DISC_OPEN "  contact = sticky\n}\n",
   CASE ":20: key 'body.w.contact': unknown value 'sticky' (allowed: \"noslip\", "
   "\"frictionless\", \"friction\")"},
  {BASE DISC_OPEN "  friction = 0.2\n}\n",
   CASE ":20: key 'body.w.friction': friction = 0.2 with contact = \"noslip\": the coefficient "
   "belongs to contact = \"friction\" (allowed: contact = \"friction\", or friction = 0)"},
  {BASE DISC_OPEN "  contact = frictionless\n  friction = 0.2\n}\n",
   CASE ":21: key 'body.w.friction': friction = 0.2 with contact = \"frictionless\": the "
   "coefficient belongs to contact = \"friction\" (allowed: contact = \"friction\", or "
   "friction = 0)"},
  {BASE DISC_OPEN "  contact = friction\n}\n",
   CASE ":16: key 'body.w.friction': contact = \"friction\" with friction = 0 (allowed: "
   "friction > 0 with contact = \"friction\")"},
  {BASE DISC_OPEN "  contact = friction\n  friction = 11\n}\n",
   CASE ":21: key 'body.w.friction': value 11 out of range (allowed: 0 ... 10)"},
  /* the tables */
  {BASE DISC_OPEN "  t = {0,\n    1,\n    1,\n    2}\n}\n",
   CASE ":22: key 'body.w.t': value 1 is not larger than the one before it, 1 (allowed: "
   "strictly increasing values)"},
  {BASE DISC_OPEN "  t = {1, 0.5}\n}\n",
   CASE ":20: key 'body.w.t': value 0.5 is not larger than the one before it, 1 (allowed: "
   "strictly increasing values)"},
  {BASE DISC_OPEN "  t = {0, -1}\n}\n",
   CASE ":20: key 'body.w.t': value -1 out of range (allowed: 0 ... 1e9 s)"},
  {BASE DISC_OPEN "  t = {0, 1, 2}\n  vx = {0, 1}\n}\n",
   CASE ":21: key 'body.w.vx': vx has 2 values, t has 3 (allowed: 1 value, or as many as t)"},
  {BASE DISC_OPEN "  vy = {0, 1, 2}\n  t = {0, 1}\n}\n",
   CASE ":21: key 'body.w.t': vy has 3 values, t has 2 (allowed: 1 value, or as many as t)"},
  {BASE DISC_OPEN "  omega = {0, 1}\n}\n",
   CASE ":20: key 'body.w.omega': omega has 2 values, t has 0 (allowed: 1 value, or as many "
   "as t)"},
  {BASE DISC_OPEN "  vx = {1e5}\n}\n",
   CASE ":20: key 'body.w.vx': value 1e5 out of range (allowed: -10000 ... 10000 m/s)"},
  /* a free motion */
  {BASE DISC_OPEN "  free_x = true\n}\n",
   CASE ":20: key 'body.w.free_x': free axis without a mass, mass = 0 (allowed: mass > 0 with "
   "free_x = true, or free_x = false)"},
  {BASE DISC_OPEN "  inertia = 1\n  free_y = yes\n}\n",
   CASE ":21: key 'body.w.free_y': free axis without a mass, mass = 0 (allowed: mass > 0 with "
   "free_y = true, or free_y = false)"},
  {BASE DISC_OPEN "  mass = 1\n  free_rotation = on\n}\n",
   CASE ":21: key 'body.w.free_rotation': free rotation without an inertia, inertia = 0 "
   "(allowed: inertia > 0 with free_rotation = true, or free_rotation = false)"},
  {BASE DISC_OPEN "  free_x = maybe\n}\n",
   CASE ":20: key 'body.w.free_x': expected true or false, got 'maybe' (allowed: true, false, "
   "yes, no, on, off)"},
  {BASE DISC_OPEN "  damping = -1\n}\n",
   CASE ":20: key 'body.w.damping': value -1 out of range (allowed: 0 ... 1e6 1/s)"},
  {BASE DISC_OPEN "  mass = -1\n}\n",
   CASE ":20: key 'body.w.mass': value -1 out of range (allowed: 0 ... 1e12 kg/m)"},
  /* the keys of 3D runs in a plane one */
  {BASE DISC_OPEN "  cz = 0.1\n}\n",
   CASE ":20: key 'body.w.cz': a key of 3D runs, set in a plane one (allowed: with mesh.nz > 0 "
   "only)"},
  {BASE DISC_OPEN "  axis = x\n}\n",
   CASE ":20: key 'body.w.axis': a key of 3D runs, set in a plane one (allowed: with mesh.nz > "
   "0 only)"},
  {BASE DISC_OPEN "  length = 1\n}\n",
   CASE ":20: key 'body.w.length': a key of 3D runs, set in a plane one (allowed: with mesh.nz "
   "> 0 only)"},
  {BASE DISC_OPEN "  vz = {1}\n}\n",
   CASE ":20: key 'body.w.vz': a key of 3D runs, set in a plane one (allowed: with mesh.nz > 0 "
   "only)"},
  {BASE DISC_OPEN "  free_z = false\n}\n",
   CASE ":20: key 'body.w.free_z': a key of 3D runs, set in a plane one (allowed: with mesh.nz "
   "> 0 only)"},
  {BASE DISC_OPEN "  fz = 1\n}\n",
   CASE ":20: key 'body.w.fz': a key of 3D runs, set in a plane one (allowed: with mesh.nz > 0 "
   "only)"},
  /* 3D */
  {BASE3 "body p {\n  shape = polygon\n  axis = x\n  cx = 0.2\n  cy = 0.2\n  cz = 0.2\n"
   "  x = {0, 0.1, 0}\n  y = {0, 0, 0.1}\n}\n",
   CASE ":22: key 'body.p.axis': shape = \"polygon\" with axis = \"x\" (allowed: axis \"z\" for a "
   "polygon; a disc or a box along any axis)"},
  {BASE3 "body d {\n  cx = 0.2\n  cy = 0.2\n  cz = 0.5\n  radius = 0.1\n}\n",
   CASE ":23: key 'body.d.cz': cz = 0.5 lies outside the mesh (allowed: 0 ... 0.4 m)"},
  {BASE3 "body d {\n  cx = 0.2\n  cy = 0.2\n  radius = 0.1\n  length = -1\n}\n",
   CASE ":24: key 'body.d.length': value -1 out of range (allowed: 0 ... 1e9 m)"},
  {BASE3 "body d {\n  cx = 0.2\n  cy = 0.2\n  radius = 0.1\n  axis = w\n}\n",
   CASE ":24: key 'body.d.axis': unknown value 'w' (allowed: \"x\", \"y\", \"z\")"},
  {BASE3 "body d {\n  cx = 0.2\n  cy = 0.2\n  radius = 0.1\n  free_z = true\n}\n",
   CASE ":24: key 'body.d.free_z': free axis without a mass, mass = 0 (allowed: mass > 0 with "
   "free_z = true, or free_z = false)"},
  {BASE3 "body d {\n  cx = 0.2\n  cy = 0.2\n  radius = 0.1\n  t = {0, 1}\n  vz = {0, 1, 2}\n}\n",
   CASE ":25: key 'body.d.vz': vz has 3 values, t has 2 (allowed: 1 value, or as many as t)"},
  /* titles */
  {BASE "body \"my wheel\" {\n  cx = 0.5\n  cy = 0.7\n  radius = 0.1\n}\n",
   CASE ":16: body title 'my wheel' (allowed: 1 ... 31 letters, digits, '_' or '-')"},
  {BASE DISC DISC, CASE ":21: a second body titled 'w' (allowed: a different title for each "
   "body)"},
  {BASE "body {\n  cx = 0.5\n}\n",
   CASE ":16: section 'body' needs a title (allowed: body NAME { ... })"},
  {BASE DISC_OPEN "  speed = 1\n}\n",
   CASE ":20: unknown key 'body.w.speed' (allowed keys in 'body': " BODY_KEYS ")"},
};

START_TEST(t_bad_body)
{
  expect_error(bad_bodies[_i].text, NULL, bad_bodies[_i].msg);
}
END_TEST

/* At most MPM_MAX_BODIES bodies; a list of times holds at most
 * MPM_MAX_POLY values. */
START_TEST(t_bad_body_counts)
{
  char text[4096] = BASE;
  for (int i = 0; i <= MPM_MAX_BODIES; i++)  /* 5 lines each, from line 16 */
    snprintf(text + strlen(text), sizeof text - strlen(text),
             "body b%d {\n  cx = 0.5\n  cy = 0.5\n  radius = 0.1\n}\n", i + 1);
  expect_error(text, NULL, CASE ":56: body 'b9' is body number 9 (allowed: at most 8 body "
               "sections)");
  snprintf(text, sizeof text, "%s", BASE DISC_OPEN "  t = {0");
  for (int i = 1; i <= MPM_MAX_POLY; i++)
    snprintf(text + strlen(text), sizeof text - strlen(text), ", %d", i);
  strcat(text, "}\n}\n");
  expect_error(text, NULL, CASE ":20: key 'body.w.t': more than 64 values (allowed: at most 64 "
               "values)");
}
END_TEST

static Suite *input_body_suite(void)
{
  Suite *s = suite_create("input_body");
  TCase *tc = tcase_create("good");
  tcase_add_test(tc, t_body_defaults);
  tcase_add_test(tc, t_bodies3);
  tcase_add_test(tc, t_body_overrides);
  suite_add_tcase(s, tc);

  TCase *bad = tcase_create("bad");
  tcase_add_loop_test(bad, t_bad_body, 0, (int)(sizeof bad_bodies / sizeof bad_bodies[0]));
  tcase_add_test(bad, t_bad_body_counts);
  suite_add_tcase(s, bad);
  return s;
}

int main(void)
{
  SRunner *sr = srunner_create(input_body_suite());
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  remove(CASE);
  remove(TMP_DIR);
  return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
