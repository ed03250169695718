/* test_bc.c: face boundary conditions (bc/bc.h) on meshes of either
 * dimension with an offset origin and unequal unit sizes. Every kind on
 * every face (the plane's edges, a box's faces) constrains exactly the
 * face's nodes with the expected bits; with all faces walls, edge and
 * corner nodes take the union (counts of one-, two- and three-bit nodes
 * exact); applying zeroes exactly the constrained components; periodic
 * faces not in pairs or not matching the mesh are refused; on boxes a
 * rectangular and a disc outlet free exactly the face nodes inside them (a
 * direct count) once opened, and none before; their open unit faces are
 * those with four freed corners; held ends keep an outlet's boundary nodes
 * but on a symmetry face; a wall polygon is its prism along z; bad outlets
 * are refused. (The plane's outlets and staircase walls: test_silo.c.) */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bc/bc.h"
#include "core/config.h"
#include "mesh/mesh.h"

/* A mesh of boxes (nz > 0) or of the plane (nz = 0). */
static void mesh_of(mpm_mesh *m, int nx, int ny, int nz)
{
  memset(m, 0, sizeof *m);
  m->dim = nz > 0 ? 3 : 2;
  m->nx = nx;
  m->ny = ny;
  m->nz = nz;
  m->x0 = 1.0;
  m->y0 = -2.0;
  m->z0 = 0.5;
  m->dx = 0.5;
  m->dy = 0.25;
  m->dz = 0.4;
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh_setup(m, &err) == MPM_OK, "%s", err.msg);
}

/* The test's own statement of the rule: bits of kind k on a face normal to
 * axis a. */
static unsigned char expected_bits(int k, int a)
{
  const unsigned char axis[3] = {MPM_FIX_X, MPM_FIX_Y, MPM_FIX_Z};
  if (k == MPM_BC_NOSLIP)
    return MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z;   /* on boxes (the plane's: x, y) */
  if (k == MPM_BC_FRICTIONLESS || k == MPM_BC_SYMMETRY)
    return axis[a];
  return 0;
}

static int on_face(const mpm_mesh *m, int f, int i, int j, int k)
{
  const int ijk[3] = {i, j, k}, n[3] = {m->nx, m->ny, m->nz};
  return ijk[f / 2] == (f % 2 ? n[f / 2] : 0);
}

static int nbits(unsigned char b)
{
  return (b & 1) + (b >> 1 & 1) + (b >> 2 & 1) + (b >> 3 & 1);
}

START_TEST(each_kind_on_each_face)
{
  mpm_mesh m;
  mesh_of(&m, 4, 3, 5);
  const int n[3] = {4, 3, 5};
  const int kinds[4] = {MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FRICTIONLESS, MPM_BC_SYMMETRY};
  for (int f = 0; f < 6; f++)
    for (int q = 0; q < 4; q++) {
      int face[6] = {0};
      face[f] = kinds[q];
      mpm_bc bc = {0};
      mpm_err err = {0};
      ck_assert_msg(mpm_bc_setup(&bc, &m, face, &err) == MPM_OK, "%s", err.msg);
      const unsigned char want = expected_bits(kinds[q], f / 2);
      int held = 0;
      for (int k = 0; k <= m.nz; k++)
        for (int j = 0; j <= m.ny; j++)
          for (int i = 0; i <= m.nx; i++) {
            const unsigned char b = bc.fix[mpm_mesh_node(&m, i, j, k)];
            ck_assert_uint_eq(b, on_face(&m, f, i, j, k) ? want : 0);
            held += b != 0;
          }
      const int a = f / 2, face_nodes = (n[(a + 1) % 3] + 1) * (n[(a + 2) % 3] + 1);
      ck_assert_int_eq(held, want ? face_nodes : 0);
      mpm_bc_clear(&bc);
    }
}
END_TEST

/* All six faces frictionless: face-interior nodes hold one component, edge
 * nodes two, the 8 corners all three. */
START_TEST(edges_and_corners_take_the_union)
{
  mpm_mesh m;
  mesh_of(&m, 4, 3, 5);
  const int nx = 4, ny = 3, nz = 5;
  int face[6];
  for (int f = 0; f < 6; f++)
    face[f] = MPM_BC_FRICTIONLESS;
  mpm_bc bc = {0};
  mpm_err err = {0};
  ck_assert_msg(mpm_bc_setup(&bc, &m, face, &err) == MPM_OK, "%s", err.msg);
  int count[4] = {0};
  for (int id = 0; id < m.nnodes; id++)
    count[nbits(bc.fix[id])]++;
  ck_assert_int_eq(count[3], 8);
  ck_assert_int_eq(count[2], 4 * ((nx - 1) + (ny - 1) + (nz - 1)));
  ck_assert_int_eq(count[1], 2 * ((ny - 1) * (nz - 1) + (nx - 1) * (nz - 1) + (nx - 1) * (ny - 1)));
  ck_assert_int_eq(count[0], (nx - 1) * (ny - 1) * (nz - 1));
  /* the edge x = x0, z = z0 holds x and z, the corner all three */
  ck_assert_uint_eq(bc.fix[mpm_mesh_node(&m, 0, 1, 0)], MPM_FIX_X | MPM_FIX_Z);
  ck_assert_uint_eq(bc.fix[mpm_mesh_node(&m, nx, ny, nz)], MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z);
  mpm_bc_clear(&bc);

  /* mixed: -z noslip, +x symmetry, the rest free; their shared edge holds
   * all three, the +x face alone only x */
  const int mixed[6] = {MPM_BC_FREE, MPM_BC_SYMMETRY, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_NOSLIP,
                        MPM_BC_FREE};
  ck_assert_msg(mpm_bc_setup(&bc, &m, mixed, &err) == MPM_OK, "%s", err.msg);
  ck_assert_uint_eq(bc.fix[mpm_mesh_node(&m, nx, 1, 0)], MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z);
  ck_assert_uint_eq(bc.fix[mpm_mesh_node(&m, nx, 1, 2)], MPM_FIX_X);
  ck_assert_uint_eq(bc.fix[mpm_mesh_node(&m, 0, 1, 2)], 0);
  int held = 0;
  for (int id = 0; id < m.nnodes; id++)
    held += bc.fix[id] != 0;
  ck_assert_int_eq(held, (nx + 1) * (ny + 1) + (ny + 1) * (nz + 1) - (ny + 1));
  mpm_bc_clear(&bc);
}
END_TEST

START_TEST(apply_zeroes_exactly_the_held_components)
{
  mpm_mesh m;
  mesh_of(&m, 4, 3, 5);
  const int face[6] = {MPM_BC_NOSLIP, MPM_BC_FRICTIONLESS, MPM_BC_SYMMETRY,
                       MPM_BC_FRICTIONLESS, MPM_BC_FREE, MPM_BC_SYMMETRY};
  mpm_bc bc = {0};
  mpm_err err = {0};
  ck_assert_msg(mpm_bc_setup(&bc, &m, face, &err) == MPM_OK, "%s", err.msg);
  const unsigned char bit[3] = {MPM_FIX_X, MPM_FIX_Y, MPM_FIX_Z};
  int seen[16] = {0};
  for (int id = 0; id < m.nnodes; id++) {
    double v[3] = {1.5, -2.5, 3.5};
    const double v0[3] = {1.5, -2.5, 3.5};
    mpm_bc_apply_node(&bc, id, 3, v);
    for (int c = 0; c < 3; c++)
      ck_assert(v[c] == ((bc.fix[id] & bit[c]) ? 0.0 : v0[c]));
    seen[bc.fix[id]] = 1;
  }
  /* the free, one-, two- and three-component masks all occurred */
  ck_assert(seen[0] && seen[MPM_FIX_X] && seen[MPM_FIX_Y] && seen[MPM_FIX_Z]);
  ck_assert(seen[MPM_FIX_Y | MPM_FIX_Z] && seen[MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z]);
  mpm_bc_clear(&bc);
}
END_TEST

START_TEST(periodic_faces_in_pairs_matching_the_mesh)
{
  mpm_mesh m;
  memset(&m, 0, sizeof m);
  m.dim = 3;
  m.nx = 4;
  m.ny = 3;
  m.nz = 5;
  m.dx = m.dy = m.dz = 0.5;
  m.periodic_x = 1;
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh_setup(&m, &err) == MPM_OK, "%s", err.msg);
  mpm_bc bc = {0};
  const int P = MPM_BC_PERIODIC, W = MPM_BC_NOSLIP;
  const int good[6] = {P, P, W, W, MPM_BC_FREE, MPM_BC_FREE};
  ck_assert_msg(mpm_bc_setup(&bc, &m, good, &err) == MPM_OK, "%s", err.msg);
  /* the aliased x faces hold nothing; the y walls hold all their nodes once */
  int held = 0;
  for (int id = 0; id < m.nnodes; id++)
    held += bc.fix[id] != 0;
  ck_assert_int_eq(held, 2 * m.snx * (m.nz + 1));
  mpm_bc_clear(&bc);

  const int one[6] = {P, W, W, W, W, W};
  ck_assert_int_eq(mpm_bc_setup(&bc, &m, one, &err), MPM_EINPUT);
  ck_assert_ptr_null(bc.fix);
  const int not_periodic[6] = {W, W, W, W, W, W};
  ck_assert_int_eq(mpm_bc_setup(&bc, &m, not_periodic, &err), MPM_EINVAL);
  const int wrong_axis[6] = {P, P, W, W, P, P};
  ck_assert_int_eq(mpm_bc_setup(&bc, &m, wrong_axis, &err), MPM_EINVAL);
  const int unknown[6] = {P, P, W, W, W, 99};
  ck_assert_int_eq(mpm_bc_setup(&bc, &m, unknown, &err), MPM_EINVAL);
  ck_assert_ptr_null(bc.fix);
}
END_TEST

/* A box outlet [lo, hi] on face f (the rectangle of a box's face). */
static int set_box(mpm_bc *bc, const mpm_mesh *m, int f, const double lo[2], const double hi[2],
                   int closed, int held_ends, mpm_err *err)
{
  return mpm_bc_set_outlet(bc, m, f, MPM_BC_OUTLET_BOX, lo, hi, closed, held_ends, err);
}

/* A disc outlet of centre c and radius r on face f: the disc inscribed in
 * the square [c - r, c + r]^2 of the face's axes. */
static int set_disc(mpm_bc *bc, const mpm_mesh *m, int f, const double c[2], double r,
                    int closed, int held_ends, mpm_err *err)
{
  const double lo[2] = {c[0] - r, c[1] - r}, hi[2] = {c[0] + r, c[1] + r};
  return mpm_bc_set_outlet(bc, m, f, MPM_BC_OUTLET_DISC, lo, hi, closed, held_ends, err);
}

/* Number of face-f nodes whose position in the face's axes satisfies the
 * outlet, counted directly; and check that exactly those are free in bc's
 * open mask and that none is free before opening. */
static int direct_count(const mpm_mesh *m, int f, int disc, const double a[2],
                        const double b[2], double r, int inside[])
{
  int ax[2];
  mpm_bc_face_axes(3, f, ax);
  int count = 0;
  for (int k = 0; k <= m->nz; k++)
    for (int j = 0; j <= m->ny; j++)
      for (int i = 0; i <= m->nx; i++) {
        const int id = mpm_mesh_node(m, i, j, k);
        inside[id] = 0;
        if (!on_face(m, f, i, j, k))
          continue;
        double x[3];
        mpm_mesh_node_pos(m, i, j, k, x);
        const double s = x[ax[0]], t = x[ax[1]];
        inside[id] = disc ? hypot(s - a[0], t - a[1]) < r
                          : s > a[0] && s < b[0] && t > a[1] && t < b[1];
        count += inside[id];
      }
  return count;
}

/* The outlet tests' mesh of 6 x 5 x 7 boxes with no-slip faces. */
static void noslip_box(mpm_mesh *m, mpm_bc *bc)
{
  mesh_of(m, 6, 5, 7);
  int face[6];
  for (int q = 0; q < 6; q++)
    face[q] = MPM_BC_NOSLIP;
  mpm_err err = {0};
  ck_assert_msg(mpm_bc_setup(bc, m, face, &err) == MPM_OK, "%s", err.msg);
}

static void check_outlet(int f, int disc, const double a[2], const double b[2], double r,
                         int min_count)
{
  mpm_mesh m;
  mpm_bc bc = {0};
  mpm_err err = {0};
  noslip_box(&m, &bc);
  int rc = disc ? set_disc(&bc, &m, f, a, r, MPM_BC_FRICTIONLESS, 0, &err)
                : set_box(&bc, &m, f, a, b, MPM_BC_FRICTIONLESS, 0, &err);
  ck_assert_msg(rc == MPM_OK, "%s", err.msg);
  int *inside = malloc(sizeof(int) * (size_t)m.nnodes);
  const int want = direct_count(&m, f, disc, a, b, r, inside);
  ck_assert_int_ge(want, min_count);

  int held = 0;            /* closed: every boundary node still held */
  for (int id = 0; id < m.nnodes; id++) {
    held += bc.fix[id] != 0;
    if (inside[id])       /* the closed frictionless wall: normal only */
      ck_assert_uint_eq(bc.fix[id], expected_bits(MPM_BC_FRICTIONLESS, f / 2));
  }
  ck_assert_int_eq(held, m.nnodes - (m.nx - 1) * (m.ny - 1) * (m.nz - 1));

  mpm_bc_open_outlet(&bc);
  int freed = 0;
  for (int id = 0; id < m.nnodes; id++) {
    const int on_boundary = bc.mask[0][id] != 0;
    if (on_boundary && bc.fix[id] == 0) {
      ck_assert(inside[id]);
      freed++;
    } else if (on_boundary) {
      ck_assert(!inside[id]);
      ck_assert_uint_eq(bc.fix[id], MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z);
    }
  }
  ck_assert_int_eq(freed, want);
  double v[3] = {1.0, 2.0, 3.0};
  for (int id = 0; id < m.nnodes; id++)
    if (inside[id]) {
      mpm_bc_apply_node(&bc, id, 3, v);
      ck_assert(v[0] == 1.0 && v[1] == 2.0 && v[2] == 3.0);
    }
  free(inside);
  mpm_bc_clear(&bc);
}

START_TEST(rectangle_outlet_frees_the_nodes_inside)
{
  /* -z face (axes x, y), x0 = 1, dx = 0.5; y0 = -2, dy = 0.25: bounds off
   * the nodes, so "inside" has no ties */
  const double lo[2] = {1.7, -1.6}, hi[2] = {3.3, -0.9};
  check_outlet(MPM_FACE_ZLO, 0, lo, hi, 0.0, 6);
  /* +x face (axes y, z) */
  const double lo2[2] = {-1.9, 1.1}, hi2[2] = {-1.1, 2.3};
  check_outlet(MPM_FACE_XHI, 0, lo2, hi2, 0.0, 6);
}
END_TEST

START_TEST(disc_outlet_frees_the_nodes_inside)
{
  /* +y face (axes x, z): centre on no node, radius off every node distance */
  const double c[2] = {2.6, 1.9};
  check_outlet(MPM_FACE_YHI, 1, c, c, 0.93, 6);
  /* -z face (axes x, y) */
  const double c2[2] = {2.4, -1.4};
  check_outlet(MPM_FACE_ZLO, 1, c2, c2, 0.55, 6);
}
END_TEST

/* The unit faces of an outlet are exactly those whose four corners the
 * outlet frees, checked unit by unit against the nodes counted directly:
 * for a rectangle the range of mpm_bc_outlet_faces (along the normal it
 * covers the mesh), for a disc mpm_bc_outlet_face_open, within that range
 * (their bounding box). */
static void check_outlet_faces(int f, const double a[2], const double b[2])
{
  mpm_mesh m;
  mpm_bc bc = {0};
  mpm_err err = {0};
  noslip_box(&m, &bc);
  ck_assert_msg(set_box(&bc, &m, f, a, b, MPM_BC_NOSLIP, 0, &err) == MPM_OK,
                "%s", err.msg);
  int *inside = malloc(sizeof(int) * (size_t)m.nnodes);
  direct_count(&m, f, 0, a, b, 0.0, inside);
  int lo[3], hi[3];
  ck_assert_int_eq(mpm_bc_outlet_faces(&bc, &m, lo, hi), f);
  const int n[3] = {m.nx, m.ny, m.nz};
  ck_assert_int_eq(lo[f / 2], 0);
  ck_assert_int_eq(hi[f / 2], n[f / 2]);
  int ax[2];
  mpm_bc_face_axes(3, f, ax);
  int open = 0;
  for (int u = 0; u < n[ax[0]]; u++)
    for (int v = 0; v < n[ax[1]]; v++) {
      int all = 1;
      for (int du = 0; du <= 1; du++)
        for (int dv = 0; dv <= 1; dv++) {
          int ijk[3];
          ijk[f / 2] = f % 2 ? n[f / 2] : 0;
          ijk[ax[0]] = u + du;
          ijk[ax[1]] = v + dv;
          all &= inside[mpm_mesh_node(&m, ijk[0], ijk[1], ijk[2])];
        }
      const int in_range = u >= lo[ax[0]] && u < hi[ax[0]] && v >= lo[ax[1]] && v < hi[ax[1]];
      ck_assert_int_eq(in_range, all);
      open += all;
    }
  ck_assert_int_ge(open, 2);
  /* a disc: mpm_bc_outlet_face_open marks exactly the unit faces with four
   * corners in it, and the range is their bounding box */
  const double c[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}, r = 0.93;
  ck_assert_msg(set_disc(&bc, &m, f, c, r, MPM_BC_NOSLIP, 0, &err) == MPM_OK,
                "%s", err.msg);
  direct_count(&m, f, 1, c, c, r, inside);
  ck_assert_int_eq(mpm_bc_outlet_faces(&bc, &m, lo, hi), f);
  int blo[2] = {1 << 20, 1 << 20}, bhi[2] = {-1, -1};
  open = 0;
  for (int u = 0; u < n[ax[0]]; u++)
    for (int v = 0; v < n[ax[1]]; v++) {
      int all = 1, ijk[3];
      for (int du = 0; du <= 1; du++)
        for (int dv = 0; dv <= 1; dv++) {
          ijk[f / 2] = f % 2 ? n[f / 2] : 0;
          ijk[ax[0]] = u + du;
          ijk[ax[1]] = v + dv;
          all &= inside[mpm_mesh_node(&m, ijk[0], ijk[1], ijk[2])];
        }
      int cu[3] = {0, 0, 0};
      cu[ax[0]] = u;
      cu[ax[1]] = v;
      ck_assert_int_eq(mpm_bc_outlet_face_open(&bc, &m, cu), all);
      if (all) {
        open++;
        blo[0] = u < blo[0] ? u : blo[0];
        blo[1] = v < blo[1] ? v : blo[1];
        bhi[0] = u + 1 > bhi[0] ? u + 1 : bhi[0];
        bhi[1] = v + 1 > bhi[1] ? v + 1 : bhi[1];
      }
    }
  ck_assert_int_ge(open, 2);
  ck_assert_int_eq(lo[ax[0]], blo[0]);
  ck_assert_int_eq(hi[ax[0]], bhi[0]);
  ck_assert_int_eq(lo[ax[1]], blo[1]);
  ck_assert_int_eq(hi[ax[1]], bhi[1]);
  free(inside);
  mpm_bc_clear(&bc);
}

START_TEST(outlet_faces_have_four_free_corners)
{
  const double lo[2] = {1.7, -1.6}, hi[2] = {3.3, -0.9};
  check_outlet_faces(MPM_FACE_ZLO, lo, hi);
  const double lo2[2] = {-1.9, 1.1}, hi2[2] = {-1.1, 2.3};
  check_outlet_faces(MPM_FACE_XHI, lo2, hi2);
}
END_TEST

/* A wall polygon in 3D is its prism along z: the right triangle of the
 * plane test (test_silo.c: nodes with i + j <= 4 held on 8 x 8 units of
 * 0.25) at every z layer, holding z too where it holds x and y (no-slip, or
 * solid), and only the side's normal (45 degrees) at the nodes of units the
 * side cuts: there a vector keeps its component along the side and along z. */
START_TEST(wall_polygon_is_a_prism)
{
  mpm_mesh m;
  memset(&m, 0, sizeof m);
  m.dim = 3;
  m.nx = m.ny = 8;
  m.nz = 3;
  m.dx = m.dy = 0.25;
  m.dz = 0.1;
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh_setup(&m, &err) == MPM_OK, "%s", err.msg);
  int face[6];
  for (int q = 0; q < 6; q++)
    face[q] = MPM_BC_FREE;
  const double px[3] = {0.0, 1.0, 0.0}, py[3] = {0.0, 0.0, 1.0};
  const unsigned char all = MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z;
  for (int kind = MPM_BC_NOSLIP; kind <= MPM_BC_FRICTIONLESS; kind++) {
    mpm_bc bc = {0};
    int held = -1;
    ck_assert_msg(mpm_bc_setup(&bc, &m, face, &err) == MPM_OK, "%s", err.msg);
    ck_assert_msg(mpm_bc_add_polygon(&bc, &m, 3, px, py, kind, &held, &err) == MPM_OK, "%s",
                  err.msg);
    ck_assert_int_eq(held, 15 * 4);
    int oblique = 0;
    for (int k = 0; k <= m.nz; k++)
      for (int j = 0; j <= m.ny; j++)
        for (int i = 0; i <= m.nx; i++) {
          const int id = mpm_mesh_node(&m, i, j, k);
          const unsigned char f = bc.fix[id];
          if (i + j > 4)
            ck_assert_int_eq(f, 0);
          else if (kind == MPM_BC_NOSLIP || i + j < 3)
            ck_assert_int_eq(f, all);
          else if (i > 0 && j > 0) {
            ck_assert_int_eq(f, MPM_FIX_N);
            ck_assert_double_eq_tol(fabs(bc.normal[2 * id]), sqrt(0.5), 1e-15);
            ck_assert_double_eq_tol(fabs(bc.normal[2 * id + 1]), sqrt(0.5), 1e-15);
            double v[3] = {1.0, 2.0, 3.0};
            mpm_bc_apply_node(&bc, id, 3, v);
            ck_assert_double_eq_tol(v[0] * bc.normal[2 * id] + v[1] * bc.normal[2 * id + 1], 0.0,
                                    1e-15);
            ck_assert_double_eq_tol(v[0] - v[1], -1.0, 1e-15);   /* along the side: kept */
            ck_assert(v[2] == 3.0);
            oblique++;
          }
        }
    ck_assert_int_eq(oblique, kind == MPM_BC_FRICTIONLESS ? 5 * 4 : 0);   /* 5 nodes a layer */
    mpm_bc_clear(&bc);
    ck_assert_ptr_null(bc.normal);
  }
}
END_TEST

/* Held ends (outlet.ends = "fixed"): a rectangle from node to node on the
 * -z face, x in [1.5, 2.5] and y in [-1.75, -1.25] (3 x 3 nodes), frees its
 * 9 nodes, or with the ends held only the one strictly inside, (2, -1.5),
 * the 8 on its boundary keeping the face's no-slip; the open unit faces are
 * the same 2 x 2 either way. */
START_TEST(held_ends_keep_the_boundary_nodes)
{
  const double lo[2] = {1.5, -1.75}, hi[2] = {2.5, -1.25};
  for (int held = 0; held <= 1; held++) {
    mpm_mesh m;
    mpm_bc bc = {0};
    mpm_err err = {0};
    noslip_box(&m, &bc);
    ck_assert_msg(set_box(&bc, &m, MPM_FACE_ZLO, lo, hi, MPM_BC_NOSLIP,
                                               held, &err) == MPM_OK, "%s", err.msg);
    mpm_bc_open_outlet(&bc);
    int freed = 0;
    for (int j = 0; j <= m.ny; j++)
      for (int i = 0; i <= m.nx; i++) {
        const int id = mpm_mesh_node(&m, i, j, 0);
        const double x = m.x0 + i * m.dx, y = m.y0 + j * m.dy;
        const int inside = x > 1.5 - 1e-9 && x < 2.5 + 1e-9 && y > -1.75 - 1e-9 &&
                           y < -1.25 + 1e-9;
        const int strict = x > 1.5 + 1e-9 && x < 2.5 - 1e-9 && y > -1.75 + 1e-9 &&
                           y < -1.25 - 1e-9;
        const int free_node = bc.fix[id] == 0;
        ck_assert_int_eq(free_node, held ? strict : inside);
        freed += free_node;
      }
    ck_assert_int_eq(freed, held ? 1 : 9);
    int flo[3], fhi[3];
    ck_assert_int_eq(mpm_bc_outlet_faces(&bc, &m, flo, fhi), MPM_FACE_ZLO);
    ck_assert(flo[0] == 1 && fhi[0] == 3 && flo[1] == 1 && fhi[1] == 3);
    mpm_bc_clear(&bc);
  }
}
END_TEST

/* Held ends on a quarter silo: symmetry faces at x = x0 and z = z0, the rest
 * no-slip; the rectangle [x0, x0 + 2 dx] x [z0, z0 + 2 dz] on the floor. Its
 * sides on the symmetry faces are the mirror images of inner nodes and are
 * freed: the 2 x 2 nodes with i, k <= 1 (the corner node keeping both
 * symmetry normals, the others one), the 5 on the far sides held. With
 * frictionless faces instead only (1, 1) is freed; a disc of radius 2 dx
 * about the corner node (on a square mesh along the face) frees the nodes
 * strictly inside its arc either way. */
START_TEST(held_ends_on_symmetry_faces)
{
  for (int sym = 0; sym <= 1; sym++)
    for (int disc = 0; disc <= 1; disc++) {
      mpm_mesh m;
      mesh_of(&m, 6, 5, 7);
      if (disc) {                                  /* square along x and z: a round disc */
        m.dz = m.dx;
        mpm_err e0 = {0};
        ck_assert_msg(mpm_mesh_setup(&m, &e0) == MPM_OK, "%s", e0.msg);
      }
      const int k = sym ? MPM_BC_SYMMETRY : MPM_BC_FRICTIONLESS;
      int face[6] = {k, MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_NOSLIP, k, MPM_BC_NOSLIP};
      mpm_bc bc = {0};
      mpm_err err = {0};
      ck_assert_msg(mpm_bc_setup(&bc, &m, face, &err) == MPM_OK, "%s", err.msg);
      const double lo[2] = {m.x0, m.z0}, hi[2] = {m.x0 + 2 * m.dx, m.z0 + 2 * m.dz};
      const int rc = disc ? set_disc(&bc, &m, MPM_FACE_YLO, lo, 2 * m.dx,
                                                    MPM_BC_NOSLIP, 1, &err)
                          : set_box(&bc, &m, MPM_FACE_YLO, lo, hi,
                                                         MPM_BC_NOSLIP, 1, &err);
      ck_assert_msg(rc == MPM_OK, "%s", err.msg);
      mpm_bc_open_outlet(&bc);
      int freed = 0;
      for (int kk = 0; kk <= m.nz; kk++)
        for (int i = 0; i <= m.nx; i++) {
          const unsigned char f = bc.fix[mpm_mesh_node(&m, i, 0, kk)];
          const int want = disc ? i * i + kk * kk < 4 : (sym ? i <= 1 && kk <= 1 : i == 1 && kk == 1);
          const unsigned char side = (unsigned char)((i == 0 ? MPM_FIX_X : 0) |
                                                     (kk == 0 ? MPM_FIX_Z : 0));
          if (want)
            ck_assert_msg(f == side, "node (%d, 0, %d): bits %d, want %d", i, kk, f, side);
          else
            ck_assert_msg(f & MPM_FIX_Y, "node (%d, 0, %d) should stay held", i, kk);
          freed += want;
        }
      ck_assert_int_eq(freed, disc ? 4 : (sym ? 4 : 1));
      mpm_bc_clear(&bc);
    }
}
END_TEST

START_TEST(outlet_refusals)
{
  mpm_mesh m;
  mesh_of(&m, 4, 3, 5);
  int face[6] = {MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_NOSLIP,
                 MPM_BC_NOSLIP};
  mpm_bc bc = {0};
  mpm_err err = {0};
  ck_assert_msg(mpm_bc_setup(&bc, &m, face, &err) == MPM_OK, "%s", err.msg);
  const double lo[2] = {1.0, -2.0}, hi[2] = {1.0, -1.0}, c[2] = {2.0, -1.5};
  ck_assert_int_eq(set_box(&bc, &m, MPM_FACE_ZLO, lo, hi, MPM_BC_NOSLIP,
                                                0, &err), MPM_EINVAL);
  ck_assert_int_eq(set_disc(&bc, &m, MPM_FACE_ZLO, c, 0.0, MPM_BC_NOSLIP, 0, &err),
                   MPM_EINVAL);
  ck_assert_int_eq(set_disc(&bc, &m, 6, c, 0.5, MPM_BC_NOSLIP, 0, &err), MPM_EINVAL);
  ck_assert_int_eq(set_disc(&bc, &m, MPM_FACE_ZLO, c, 0.5, MPM_BC_SYMMETRY, 0,
                                           &err),
                   MPM_EINVAL);
  ck_assert_ptr_null(bc.mask[1]);
  ck_assert_int_eq(bc.out_face, -1);
  mpm_bc_open_outlet(&bc);  /* no outlet: nothing to open */
  ck_assert_ptr_eq(bc.fix, bc.mask[0]);
  mpm_bc_clear(&bc);
}
END_TEST

/* The plane: every kind on each of the four edges holds exactly the edge's
 * nodes (no-slip x and y, frictionless and symmetry the normal); all four
 * frictionless, the 4 corners hold both components, the other edge nodes
 * one; applying zeroes exactly the held components and leaves a third
 * component alone. */
START_TEST(plane_edges)
{
  mpm_mesh m;
  mesh_of(&m, 4, 3, 0);
  const int kinds[4] = {MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FRICTIONLESS, MPM_BC_SYMMETRY};
  for (int f = 0; f < 4; f++)
    for (int q = 0; q < 4; q++) {
      int face[4] = {0};
      face[f] = kinds[q];
      mpm_bc bc = {0};
      mpm_err err = {0};
      ck_assert_msg(mpm_bc_setup(&bc, &m, face, &err) == MPM_OK, "%s", err.msg);
      const unsigned char want = kinds[q] == MPM_BC_NOSLIP ? MPM_FIX_X | MPM_FIX_Y
                                                           : expected_bits(kinds[q], f / 2);
      int held = 0;
      for (int j = 0; j <= m.ny; j++)
        for (int i = 0; i <= m.nx; i++) {
          const unsigned char b = bc.fix[mpm_mesh_node(&m, i, j, 0)];
          ck_assert_uint_eq(b, on_face(&m, f, i, j, 0) ? want : 0);
          held += b != 0;
        }
      ck_assert_int_eq(held, want ? (f / 2 ? m.nx + 1 : m.ny + 1) : 0);
      mpm_bc_clear(&bc);
    }
  const int fr[4] = {MPM_BC_FRICTIONLESS, MPM_BC_FRICTIONLESS, MPM_BC_FRICTIONLESS,
                     MPM_BC_FRICTIONLESS};
  mpm_bc bc = {0};
  mpm_err err = {0};
  ck_assert_msg(mpm_bc_setup(&bc, &m, fr, &err) == MPM_OK, "%s", err.msg);
  int count[4] = {0};
  for (int id = 0; id < m.nnodes; id++)
    count[nbits(bc.fix[id])]++;
  ck_assert_int_eq(count[3], 0);
  ck_assert_int_eq(count[2], 4);
  ck_assert_int_eq(count[1], 2 * ((m.nx - 1) + (m.ny - 1)));
  ck_assert_int_eq(count[0], (m.nx - 1) * (m.ny - 1));
  mpm_bc_clear(&bc);
  const int mixed[4] = {MPM_BC_NOSLIP, MPM_BC_SYMMETRY, MPM_BC_FRICTIONLESS, MPM_BC_FREE};
  ck_assert_msg(mpm_bc_setup(&bc, &m, mixed, &err) == MPM_OK, "%s", err.msg);
  const unsigned char bit[2] = {MPM_FIX_X, MPM_FIX_Y};
  int seen[16] = {0};
  for (int id = 0; id < m.nnodes; id++) {
    double v[3] = {1.5, -2.5, 3.5};
    const double v0[3] = {1.5, -2.5, 3.5};
    mpm_bc_apply_node(&bc, id, 2, v);
    for (int c = 0; c < 2; c++)
      ck_assert(v[c] == ((bc.fix[id] & bit[c]) ? 0.0 : v0[c]));
    ck_assert(v[2] == 3.5);
    seen[bc.fix[id]] = 1;
  }
  ck_assert(seen[0] && seen[MPM_FIX_X] && seen[MPM_FIX_Y] && seen[MPM_FIX_X | MPM_FIX_Y]);
  mpm_bc_clear(&bc);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("bc");
  TCase *tc = tcase_create("faces");
  tcase_add_test(tc, each_kind_on_each_face);
  tcase_add_test(tc, edges_and_corners_take_the_union);
  tcase_add_test(tc, apply_zeroes_exactly_the_held_components);
  tcase_add_test(tc, periodic_faces_in_pairs_matching_the_mesh);
  tcase_add_test(tc, rectangle_outlet_frees_the_nodes_inside);
  tcase_add_test(tc, disc_outlet_frees_the_nodes_inside);
  tcase_add_test(tc, outlet_faces_have_four_free_corners);
  tcase_add_test(tc, wall_polygon_is_a_prism);
  tcase_add_test(tc, held_ends_keep_the_boundary_nodes);
  tcase_add_test(tc, held_ends_on_symmetry_faces);
  tcase_add_test(tc, outlet_refusals);
  tcase_add_test(tc, plane_edges);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
