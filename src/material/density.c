/* density.c: the density a point's state is decided with ([D-thesis] §3.4).
 *
 *   point   rho_p = m_p / V_p, V_p *= exp(dt tr L_p)     (local rule, eq. 3.34; [DK15])
 *   element rho_e = m_e / V_e, m_e = sum_{p in e} m_p,   (eq. 3.36-3.38; plane strain,
 *           V_e = dx dy (dx dy dz in 3D)                 per unit thickness)
 *   hybrid  point rule in boundary units, element rule in the interior (§3.4.1).
 *   unit    rho_u = sum_{p in e} m_p / sum_{p in e} V_p: the element rule with
 *           the volume the points occupy in place of the unit area, so neither
 *           quantised by the point count nor low in partly filled units. Every
 *           point of a unit gets the same state: a unit carries stress only
 *           when its points are dense on average.
 * A point belongs to the unit containing its centre. The thesis finds boundary
 * units by a Sobel filter of the point counts with an unstated threshold; here
 * a unit holding points is a boundary unit when one of the eight units around
 * it (the 3 x 3 support of that filter; 26 and 3 x 3 x 3 in 3D) holds none. A
 * partially filled unit at a free surface has empty units above it, so it is a
 * boundary unit. Units beyond a non-periodic mesh edge do not count as empty
 * (material resting on a wall is not at a free boundary); periodic edges wrap.
 * Only the state decision reads this density: V_p keeps its local update, so
 * mass is conserved point by point. The unit sums run over the points in index
 * order on one thread, so the result does not depend on the thread count. */
#include "material/density.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "core/names.h"

static const char *const rule_names[] = {
  [MPM_DENSITY_POINT] = "point", [MPM_DENSITY_ELEMENT] = "element",
  [MPM_DENSITY_HYBRID] = "hybrid", [MPM_DENSITY_UNIT] = "unit"
};

int mpm_material_density_rule_from_name(const char *name)
{
  return mpm_names_index(rule_names, MPM_NAMES_COUNT(rule_names), name);
}

const char *mpm_material_density_rule_name(int rule)
{
  return mpm_names_at(rule_names, MPM_NAMES_COUNT(rule_names), rule);
}

void mpm_material_density_free(mpm_material_density *ws)
{
  if (!ws)
    return;
  free(ws->sm);
  free(ws->sv);
  free(ws->count);
  free(ws->edge);
  free(ws);
}

int mpm_material_density_alloc(mpm_material_density **out, const mpm_mesh *m, mpm_err *err)
{
  *out = NULL;
  const size_t nu = m->nunits;
  if (nu < 1 || nu > (size_t)INT_MAX)
    return mpm_err_set(err, MPM_EINVAL, "density: mesh not set up (%d x %d x %d units)", m->nx,
                       m->ny, m->nz);
  mpm_material_density *ws = calloc(1, sizeof *ws);
  if (ws) {
    for (int a = 0; a < 3; a++) {
      ws->n[a] = m->n[a];
      ws->periodic[a] = m->periodic[a];
    }
    ws->volume = m->dx * m->dy * (m->dim == 3 ? m->dz : 1.0);
    ws->sm = calloc(nu, sizeof *ws->sm);
    ws->sv = calloc(nu, sizeof *ws->sv);
    ws->count = calloc(nu, sizeof *ws->count);
    ws->edge = calloc(nu, sizeof *ws->edge);
  }
  if (!ws || !ws->sm || !ws->sv || !ws->count || !ws->edge) {
    mpm_material_density_free(ws);
    return mpm_err_set(err, MPM_ENOMEM, "density: no memory for %zu units", nu);
  }
  *out = ws;
  return MPM_OK;
}

/* Unit of point p, c[0] + nx (c[1] + ny c[2]), from the caller's unit[] or
 * its position; -1 outside the mesh. */
static long unit_of(const mpm_mesh *m, const int *unit, const mpm_points *P, size_t p)
{
  if (unit)
    return unit[p];
  const double x[3] = {P->x[p], P->y[p], m->dim == 3 ? P->z[p] : 0.0};
  int c[3];
  if (mpm_mesh_unit(m, x, c) != MPM_OK)
    return -1;
  return (long)mpm_mesh_unit_index(m, c);
}

/* m_e, the point volume and the point count of every unit, in point order. */
static void unit_sums(mpm_material_density *ws, const mpm_mesh *m, const mpm_points *P,
                      const int *unit)
{
  const size_t nu = (size_t)ws->n[0] * (size_t)ws->n[1] * (size_t)ws->n[2];
  memset(ws->sm, 0, nu * sizeof *ws->sm);
  memset(ws->sv, 0, nu * sizeof *ws->sv);
  memset(ws->count, 0, nu * sizeof *ws->count);
  for (size_t p = 0; p < P->n; p++) {                 /* fixed order: thread-count free */
    long u = unit_of(m, unit, P, p);
    if (u < 0)
      continue;                                       /* leaving the mesh: not counted */
    size_t e = (size_t)u;
    ws->sm[e] += P->mass[p];                          /* m_e = sum m_p */
    ws->sv[e] += P->vol[p];
    ws->count[e]++;
  }
}

/* Count of unit c seen from inside: -1 beyond a non-periodic edge. */
static int count_at(const mpm_material_density *ws, int c[3])
{
  const int *n = ws->n;
  for (int a = 0; a < 3; a++)
    if (c[a] < 0 || c[a] >= n[a]) {
      if (!ws->periodic[a])
        return -1;
      c[a] = (c[a] + n[a]) % n[a];
    }
  return ws->count[(size_t)c[0] + (size_t)n[0] * ((size_t)c[1] + (size_t)n[1] * (size_t)c[2])];
}

/* edge[e] = 1 for a unit with points and an empty unit among its 8
 * neighbours (26 in 3D). */
static void mark_edges(mpm_material_density *ws)
{
  const int dk = ws->n[2] > 1 || ws->periodic[2];       /* the plane: one layer */
  size_t e = 0;
  for (int k = 0; k < ws->n[2]; k++)
    for (int j = 0; j < ws->n[1]; j++)
      for (int i = 0; i < ws->n[0]; i++, e++) {
        int edge = 0;
        for (int c2 = -dk; c2 <= dk && ws->count[e] > 0; c2++)
          for (int c1 = -1; c1 <= 1; c1++)
            for (int c0 = -1; c0 <= 1; c0++) {
              int c[3] = {i + c0, j + c1, k + c2};
              edge |= count_at(ws, c) == 0;
            }
        ws->edge[e] = (unsigned char)edge;
      }
}

void mpm_material_density_compute(mpm_material_density *ws, const mpm_mesh *m, int rule,
                                  const mpm_points *P, const int *unit, double *rho)
{
  const size_t n = P->n;
  const double *mass = P->mass, *vol = P->vol;
  if (rule == MPM_DENSITY_POINT) {
    for (size_t p = 0; p < n; p++)
      rho[p] = mass[p] / vol[p];                      /* rho_p = m_p / V_p */
    return;
  }
  unit_sums(ws, m, P, unit);
  for (int a = 0; a < 3; a++)                         /* the mesh's periodic axes */
    ws->periodic[a] = m->periodic[a];
  if (rule == MPM_DENSITY_HYBRID)
    mark_edges(ws);
  const double iarea = 1.0 / ws->volume;
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < n; p++) {
    long u = unit_of(m, unit, P, p);
    size_t e = u < 0 ? 0 : (size_t)u;
    if (u < 0 || (rule == MPM_DENSITY_HYBRID && ws->edge[e]))
      rho[p] = mass[p] / vol[p];                      /* local rule, eq. 3.34 */
    else if (rule == MPM_DENSITY_UNIT)
      rho[p] = ws->sm[e] / ws->sv[e];                 /* rho_u = sum m_p / sum V_p */
    else
      rho[p] = ws->sm[e] * iarea;                     /* rho_e = m_e / V_e, eq. 3.38 */
  }
}
