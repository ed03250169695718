/* test_density.c: unit tests of the density of the state decision
 * ([D-thesis] §3.4; src/material/density.c): the name table and the point,
 * element, hybrid and unit rules on hand-laid blocks of points. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "material/density.h"

/* The 7 x 5 mesh of units 0.13 x 0.11 m from (-0.4, 0.25) that the blocks
 * below are laid on, periodic along x and/or y on request. */
static mpm_mesh make_mesh(int topo, int diag, int px, int py)
{
  mpm_mesh m = {.nx = 7, .ny = 5, .x0 = -0.4, .y0 = 0.25, .dx = 0.13, .dy = 0.11,
                .topology = topo, .diagonal = diag, .periodic_x = px, .periodic_y = py};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  return m;
}

/* ---- density of the state decision ([D-thesis] §3.4) ---------------------
 * Points are laid out 2 x 2 per unit at the quarter positions of the units
 * listed, each with mass PM and volume PV = 0.8 dx dy / 4, so m / V is 1.25
 * times the element value of a unit of 4 points (4 PM / (dx dy)) and each
 * point's result says which rule it got. The element value is 4
 * additions and a product: within a few 1e-16 relative of the exact value,
 * and a unit that counted one point too many or too few is 25 % off; 1e-14
 * relative separates the two with room. */
#define PM 0.7
#define PV (0.8 * 0.13 * 0.11 / 4.0)  /* 0.8 of a quarter unit: m / V = 1.25 m / (dx dy / 4) */
#define MAXP 256

typedef struct pointset {
  size_t n;
  double x[MAXP], y[MAXP], m[MAXP], v[MAXP], rho[MAXP];
  int ui[MAXP], uj[MAXP];  /* the unit each point was placed in */
} pointset;

/* 2 x 2 points in every unit (i, j) with i0 <= i <= i1, j0 <= j <= j1. */
static void fill_units(pointset *ps, const mpm_mesh *m, int i0, int i1, int j0, int j1)
{
  for (int j = j0; j <= j1; j++)
    for (int i = i0; i <= i1; i++)
      for (int k = 0; k < 4; k++) {
        size_t p = ps->n++;
        ck_assert_uint_lt(p, MAXP);
        ps->x[p] = m->x0 + (i + 0.25 + 0.5 * (k % 2)) * m->dx;
        ps->y[p] = m->y0 + (j + 0.25 + 0.5 * (k / 2)) * m->dy;
        ps->m[p] = PM;
        ps->v[p] = PV;
        ps->ui[p] = i;
        ps->uj[p] = j;
      }
}

/* A point store holding the points of ps (positions, masses, volumes). */
static mpm_points *store_of(const pointset *ps, int dim)
{
  mpm_points *P = mpm_points_alloc_dim(ps->n, dim);
  ck_assert_ptr_nonnull(P);
  for (size_t p = 0; p < ps->n; p++) {
    size_t q;
    ck_assert_int_eq(mpm_points_push(P, &q), MPM_OK);
    P->x[q] = ps->x[p];
    P->y[q] = ps->y[p];
    P->mass[q] = ps->m[p];
    P->vol[q] = ps->v[p];
  }
  return P;
}

static void compute(mpm_material_density *ws, const mpm_mesh *m, int rule, pointset *ps)
{
  mpm_points *P = store_of(ps, 2);
  mpm_material_density_compute(ws, m, rule, P, NULL, ps->rho);
  mpm_points_free(P);
}

static mpm_material_density *density_ws(const mpm_mesh *m)
{
  mpm_material_density *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_material_density_alloc(&ws, m, &err), MPM_OK);
  return ws;
}

static int near_rel(double a, double b)
{
  return fabs(a - b) <= 1e-14 * fabs(b);
}

/* Unit rule: rho_u = sum m_p / sum V_p over the points whose centre lies in
 * the unit. Volumes differing point by point within a unit give one value
 * for all its points (the volume-weighted harmonic mean, not the count over
 * the unit area); a unit holding 3 points reads the same as one holding 4
 * when their volumes agree (no quantisation by the count). */
START_TEST(t_density_unit_block)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  mpm_material_density *ws = density_ws(&m);
  pointset ps = {0};
  fill_units(&ps, &m, 1, 4, 1, 2);
  double sv[64] = {0}, sm[64] = {0};
  for (size_t p = 0; p < ps.n; p++) {
    ps.v[p] = PV * (0.7 + 0.1 * (double)(p % 7));   /* 0.7 ... 1.3 PV */
    ps.m[p] = PM * (1.0 + 0.05 * (double)(p % 3));
  }
  ps.n -= 1;                                        /* unit (4, 2) keeps 3 points */
  for (size_t p = 0; p < ps.n; p++) {
    int e = ps.ui[p] + m.nx * ps.uj[p];
    sv[e] += ps.v[p];
    sm[e] += ps.m[p];
  }
  compute(ws, &m, MPM_DENSITY_UNIT, &ps);
  for (size_t p = 0; p < ps.n; p++) {
    int e = ps.ui[p] + m.nx * ps.uj[p];
    double want = sm[e] / sv[e];
    ck_assert_msg(near_rel(ps.rho[p], want), "point %zu: %.17g, want %.17g", p, ps.rho[p], want);
  }
  /* equal volumes: 3 points read the point density as 4 do */
  for (size_t p = 0; p < ps.n; p++) {
    ps.v[p] = PV;
    ps.m[p] = PM;
  }
  compute(ws, &m, MPM_DENSITY_UNIT, &ps);
  for (size_t p = 0; p < ps.n; p++)
    ck_assert_msg(near_rel(ps.rho[p], PM / PV), "point %zu: %.17g", p, ps.rho[p]);
  mpm_material_density_free(ws);
}
END_TEST

START_TEST(t_density_names)
{
  ck_assert_int_eq(mpm_material_density_rule_from_name("point"), MPM_DENSITY_POINT);
  ck_assert_int_eq(mpm_material_density_rule_from_name("element"), MPM_DENSITY_ELEMENT);
  ck_assert_int_eq(mpm_material_density_rule_from_name("hybrid"), MPM_DENSITY_HYBRID);
  ck_assert_int_eq(mpm_material_density_rule_from_name("unit"), MPM_DENSITY_UNIT);
  ck_assert_int_eq(mpm_material_density_rule_from_name("nodal"), -1);
  ck_assert_str_eq(mpm_material_density_rule_name(MPM_DENSITY_HYBRID), "hybrid");
  ck_assert_str_eq(mpm_material_density_rule_name(MPM_DENSITY_UNIT), "unit");
  ck_assert_ptr_null(mpm_material_density_rule_name(4));
  ck_assert_ptr_null(mpm_material_density_rule_name(-1));
  mpm_material_density_free(NULL);
}
END_TEST

/* Point rule: m / V; element rule: a uniform block of 2 x 2 points per unit
 * gives 4 m / (dx dy) in every unit, a unit with one point more 5 m / (dx dy),
 * and a point outside the mesh keeps m / V and adds to no unit. */
START_TEST(t_density_element_block)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  mpm_material_density *ws = density_ws(&m);
  pointset ps = {0};
  fill_units(&ps, &m, 1, 5, 1, 3);
  const double area = m.dx * m.dy, rho4 = 4.0 * PM / area;
  ck_assert(fabs(PM / PV / rho4 - 1.25) < 1e-12);           /* the two rules differ */
  compute(NULL, &m, MPM_DENSITY_POINT, &ps);
  for (size_t p = 0; p < ps.n; p++)
    ck_assert(ps.rho[p] == PM / PV);
  compute(ws, &m, MPM_DENSITY_ELEMENT, &ps);
  for (size_t p = 0; p < ps.n; p++)
    ck_assert_msg(near_rel(ps.rho[p], rho4), "point %zu: %.17g, want %.17g", p, ps.rho[p], rho4);
  /* one more point in unit (3, 2), one outside the right edge */
  size_t extra = ps.n++, out = ps.n++;
  ps.x[extra] = m.x0 + 3.5 * m.dx;
  ps.y[extra] = m.y0 + 2.5 * m.dy;
  ps.x[out] = m.x0 + m.lx + 0.01;
  ps.y[out] = m.y0 + 2.5 * m.dy;
  ps.m[extra] = ps.m[out] = PM;
  ps.v[extra] = ps.v[out] = PV;
  ps.ui[extra] = 3;
  ps.uj[extra] = 2;
  compute(ws, &m, MPM_DENSITY_ELEMENT, &ps);
  for (size_t p = 0; p < ps.n - 1; p++) {
    double want = ps.ui[p] == 3 && ps.uj[p] == 2 ? 5.0 * PM / area : rho4;
    ck_assert_msg(near_rel(ps.rho[p], want), "point %zu: %.17g, want %.17g", p, ps.rho[p], want);
  }
  ck_assert(ps.rho[out] == PM / PV);
  double total = 0.0;
  for (int e = 0; e < m.nx * m.ny; e++)
    total += ws->sm[e];
  ck_assert(near_rel(total, (double)(ps.n - 1) * PM));
  ck_assert_int_eq(ws->count[3 + m.nx * 2], 5);
  ck_assert_int_eq(ws->count[0], 0);
  mpm_material_density_free(ws);
}
END_TEST

/* Hybrid, free block of 5 x 3 units: only the units whose 8 neighbours all
 * hold points, (2..4, 2), use the element density; the ring around them
 * keeps m / V. */
START_TEST(t_density_hybrid_block)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  mpm_material_density *ws = density_ws(&m);
  pointset ps = {0};
  fill_units(&ps, &m, 1, 5, 1, 3);
  compute(ws, &m, MPM_DENSITY_HYBRID, &ps);
  const double rho4 = 4.0 * PM / (m.dx * m.dy);
  int ninner = 0;
  for (size_t p = 0; p < ps.n; p++) {
    int inner = ps.ui[p] >= 2 && ps.ui[p] <= 4 && ps.uj[p] == 2;
    ninner += inner;
    if (inner)
      ck_assert_msg(near_rel(ps.rho[p], rho4), "point %zu: %.17g, want element %.17g", p,
                    ps.rho[p], rho4);
    else
      ck_assert_msg(ps.rho[p] == PM / PV, "point %zu in unit (%d, %d): %.17g, want m/V", p,
                    ps.ui[p], ps.uj[p], ps.rho[p]);
  }
  ck_assert_int_eq(ninner, 12);
  mpm_material_density_free(ws);
}
END_TEST

/* The element and hybrid rules on a 3D mesh of 5 x 4 x 5 boxes of 0.1 m
 * (with the points' boxes given, e = i + nx (j + ny k), and found from the
 * positions): one point at the centre of each box of i 1..3, j 0..2, k 0..3. Element: m / V_e in every
 * box. Hybrid: the element density only where all 26 neighbours hold points
 * or lie beyond a non-periodic face, i = 2, j 0..1 and k 0..2 (k = -1 is
 * beyond the face); with z periodic, box k = 0 sees the empty k = 4, so
 * k 1..2 only. */
START_TEST(t_density_3d_grid)
{
  const int n[3] = {5, 4, 5};
  enum { NP = 3 * 3 * 4 };
  double rho[NP];
  int unit[NP], at[NP][3], np = 0;
  mpm_points *P = mpm_points_alloc_dim(NP, 3);
  for (int k = 0; k <= 3; k++)
    for (int j = 0; j <= 2; j++)
      for (int i = 1; i <= 3; i++, np++) {
        size_t q;
        ck_assert_int_eq(mpm_points_push(P, &q), MPM_OK);
        P->x[q] = 0.1 * i + 0.05;
        P->y[q] = 0.1 * j + 0.05;
        P->z[q] = 0.1 * k + 0.05;
        P->mass[q] = PM;
        P->vol[q] = PV;
        unit[np] = i + n[0] * (j + n[1] * k);
        at[np][0] = i;
        at[np][1] = j;
        at[np][2] = k;
      }
  ck_assert_int_eq(np, NP);
  for (int pz = 0; pz <= 1; pz++) {
    mpm_mesh m = {.dim = 3, .nx = n[0], .ny = n[1], .nz = n[2], .dx = 0.1, .dy = 0.1,
                  .dz = 0.1, .periodic_z = pz};
    mpm_err err = {0};
    ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
    const double vol = m.dx * m.dy * m.dz;
    mpm_material_density *ws = NULL;
    ck_assert_int_eq(mpm_material_density_alloc(&ws, &m, &err), MPM_OK);
    mpm_material_density_compute(ws, &m, MPM_DENSITY_ELEMENT, P, unit, rho);
    for (int p = 0; p < NP; p++)
      ck_assert(near_rel(rho[p], PM / vol));
    mpm_material_density_compute(ws, &m, MPM_DENSITY_ELEMENT, P, NULL, rho);   /* from x */
    for (int p = 0; p < NP; p++)
      ck_assert(near_rel(rho[p], PM / vol));
    mpm_material_density_compute(ws, &m, MPM_DENSITY_HYBRID, P, unit, rho);
    int inner = 0;
    for (int p = 0; p < NP; p++) {
      const int k0 = pz ? 1 : 0;
      const int in = at[p][0] == 2 && at[p][1] <= 1 && at[p][2] >= k0 && at[p][2] <= 2;
      inner += in;
      ck_assert_msg(in ? near_rel(rho[p], PM / vol) : rho[p] == PM / PV,
                    "z periodic %d, box (%d, %d, %d): %g", pz, at[p][0], at[p][1], at[p][2],
                    rho[p]);
    }
    ck_assert_int_eq(inner, pz ? 4 : 6);
    mpm_material_density_free(ws);
  }
  mpm_points_free(P);
}
END_TEST

/* Hybrid at mesh edges: beyond a non-periodic edge is not empty (a corner
 * block of 3 x 2 units has interior units (0, 0) and (1, 0)); across a
 * periodic edge the unit on the other side counts (a layer of units
 * 0..5 of 7 over rows 0..1 has interior units (0..4, 0) without, but only
 * (1..4, 0) with x periodic: unit 0 then sees the empty unit 6). */
START_TEST(t_density_hybrid_edges)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  mpm_mesh mp = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 1, 0);
  mpm_material_density *ws = density_ws(&m);
  const double rho4 = 4.0 * PM / (m.dx * m.dy);
  pointset ps = {0};
  fill_units(&ps, &m, 0, 2, 0, 1);
  compute(ws, &m, MPM_DENSITY_HYBRID, &ps);
  for (size_t p = 0; p < ps.n; p++) {
    int inner = ps.ui[p] <= 1 && ps.uj[p] == 0;
    ck_assert_msg(inner ? near_rel(ps.rho[p], rho4) : ps.rho[p] == PM / PV,
                  "corner block, unit (%d, %d): %.17g", ps.ui[p], ps.uj[p], ps.rho[p]);
  }
  for (int periodic = 0; periodic <= 1; periodic++) {
    const mpm_mesh *mm = periodic ? &mp : &m;
    pointset layer = {0};
    fill_units(&layer, mm, 0, 5, 0, 1);
    compute(ws, mm, MPM_DENSITY_HYBRID, &layer);
    for (size_t p = 0; p < layer.n; p++) {
      int i = layer.ui[p], lo = periodic ? 1 : 0, hi = 4;
      int inner = layer.uj[p] == 0 && i >= lo && i <= hi;
      ck_assert_msg(inner ? near_rel(layer.rho[p], rho4) : layer.rho[p] == PM / PV,
                    "layer, periodic %d, unit (%d, %d): %.17g", periodic, i, layer.uj[p],
                    layer.rho[p]);
    }
  }
  mpm_material_density_free(ws);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("density");
  TCase *tc = tcase_create("density");
  tcase_add_test(tc, t_density_names);
  tcase_add_test(tc, t_density_element_block);
  tcase_add_test(tc, t_density_hybrid_block);
  tcase_add_test(tc, t_density_3d_grid);
  tcase_add_test(tc, t_density_hybrid_edges);
  tcase_add_test(tc, t_density_unit_block);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
