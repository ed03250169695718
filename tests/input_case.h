/* input_case.h: what the tests of the input reader share: a valid plane
 * case (BASE) and a 3D one (BASE3), bodies to append to BASE, and writing a
 * text and loading it, expecting its one error, writing a configuration as
 * text and finding a section in it. A test defines TMP_DIR, a scratch
 * directory of its own, before it includes this. */
#ifndef TESTS_INPUT_CASE_H
#define TESTS_INPUT_CASE_H

#include <check.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "core/config.h"
#include "core/error.h"
#include "io/io.h"

#ifndef TEST_SRCDIR
#define TEST_SRCDIR "."
#endif
#define CASE TMP_DIR "/case.conf"
#define GOOD TEST_SRCDIR "/tests/inputs/good/"

/* A valid case of 15 lines; text appended to it starts on line 16. */
#define BASE            \
  "mesh {\n"            \
  "  nx = 10\n"         \
  "  ny = 10\n"         \
  "  dx = 0.1\n"        \
  "  dy = 0.1\n"        \
  "}\n"                 \
  "time {\n"            \
  "  t_end = 1\n"       \
  "}\n"                 \
  "fill a {\n"          \
  "  xmin = 0\n"        \
  "  xmax = 0.5\n"      \
  "  ymin = 0\n"        \
  "  ymax = 0.5\n"      \
  "}\n"

/* A disc body after BASE on lines 16 ... 20; DISC_OPEN leaves it open after
 * line 19, so that the keys a case adds start on line 20. */
#define DISC_OPEN     \
  "body w {\n"        \
  "  cx = 0.5\n"      \
  "  cy = 0.7\n"      \
  "  radius = 0.1\n"
#define DISC DISC_OPEN "}\n"

/* A polygon body after BASE, open after line 19. */
#define POLY_OPEN           \
  "body w {\n"              \
  "  shape = polygon\n"     \
  "  cx = 0.5\n"            \
  "  cy = 0.7\n"

/* A valid 3D case of 19 lines (a mesh of 0.4 m along each axis). */
#define BASE3                                                                      \
  "mesh {\n  nx = 4\n  ny = 4\n  nz = 4\n  dx = 0.1\n  dy = 0.1\n  dz = 0.1\n}\n" \
  "time {\n  t_end = 1\n}\n"                                                        \
  "fill a {\n  xmin = 0\n  xmax = 0.2\n  ymin = 0\n  ymax = 0.2\n  zmin = 0\n"      \
  "  zmax = 0.2\n}\n"

/* The keys of a body section, as messages list them. */
#define BODY_KEYS                                                                            \
  "shape, axis, cx, cy, cz, radius, hx, hy, x, y, angle, length, side, contact, friction, t, " \
  "vx, vy, vz, omega, free_x, free_y, free_z, free_rotation, mass, inertia, fx, fy, fz, "     \
  "torque, damping, carve"

/* len bytes of text to path (in TMP_DIR, made if needed). */
static inline void write_bytes(const char *path, const char *text, size_t len)
{
  mkdir(TMP_DIR, 0777);
  FILE *f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  ck_assert_uint_eq(fwrite(text, 1, len, f), len);
  ck_assert_int_eq(fclose(f), 0);
}

/* Write text to CASE and load it with the given overrides. */
static inline int load_text(const char *text, const char *const *sets, int nsets,
                            mpm_config *cfg, mpm_err *err)
{
  write_bytes(CASE, text, strlen(text));
  return mpm_io_input_load(CASE, sets, nsets, cfg, err);
}

static inline void load_ok(const char *path, const char *const *sets, int nsets, mpm_config *cfg)
{
  mpm_err err = {0};
  int rc = mpm_io_input_load(path, sets, nsets, cfg, &err);
  ck_assert_msg(rc == MPM_OK, "%s: %s", path, err.msg);
  ck_assert_int_eq(err.code, MPM_OK);
}

static inline void expect_error(const char *text, const char *set, const char *msg)
{
  mpm_config cfg;
  mpm_err err = {0};
  const char *sets[1] = {set};
  int rc = load_text(text, sets, set ? 1 : 0, &cfg, &err);
  ck_assert_int_eq(rc, MPM_EINPUT);
  ck_assert_int_eq(err.code, MPM_EINPUT);
  ck_assert_str_eq(err.msg, msg);
}

/* cfg written with mpm_io_input_write into a string (caller frees). Not
 * inlined: GCC then takes the string for the local that open_memstream
 * filled, and warns of a dangling pointer. */
__attribute__((noinline, unused)) static char *written(const mpm_config *cfg)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  ck_assert_ptr_nonnull(f);
  ck_assert_int_eq(mpm_io_input_write(f, cfg), MPM_OK);
  ck_assert_int_eq(fclose(f), 0);
  return buf;
}

/* The text of section "SECTION TITLE" in a resolved input (caller frees). */
static inline char *item_text(const char *text, const char *section, const char *title)
{
  char head[80];
  snprintf(head, sizeof head, "%s %s {\n", section, title);
  const char *s = strstr(text, head);
  ck_assert_msg(s != NULL, "no %s '%s' in:\n%s", section, title, text);
  const char *e = strstr(s, "\n}\n");
  ck_assert_ptr_nonnull(e);
  return strndup(s, (size_t)(e - s + 1));
}

#endif
