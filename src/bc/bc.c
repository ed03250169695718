/* bc.c: face boundary conditions as a per-node mask, for a mesh of either
 * dimension (MODEL.md section 2, step 3). No-slip fixes every velocity
 * component of the nodes on the face; frictionless and symmetry fix the
 * normal one; a node on several faces takes the union. */
#include "bc/bc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/names.h"

static const char *const bc_names[] = {
  [MPM_BC_FREE] = "free",
  [MPM_BC_NOSLIP] = "noslip",
  [MPM_BC_FRICTIONLESS] = "frictionless",
  [MPM_BC_SYMMETRY] = "symmetry",
  [MPM_BC_PERIODIC] = "periodic",
};

/* The plane's edges and a box's faces, for messages. */
static const char *const face_names[2][6] = {{"left", "right", "bottom", "top", "", ""},
                                             {"-x", "+x", "-y", "+y", "-z", "+z"}};
static const char *const wall_acceleration_names[] = {"jump", "zero"};

int mpm_bc_wall_acceleration_from_name(const char *name)
{
  return mpm_names_index(wall_acceleration_names, MPM_NAMES_COUNT(wall_acceleration_names), name);
}

const char *mpm_bc_wall_acceleration_name(int rule)
{
  return mpm_names_at(wall_acceleration_names, MPM_NAMES_COUNT(wall_acceleration_names), rule);
}

int mpm_bc_kind_from_name(const char *name)
{
  return mpm_names_index(bc_names, MPM_NAMES_COUNT(bc_names), name);
}

const char *mpm_bc_kind_name(int kind)
{
  return mpm_names_at(bc_names, MPM_NAMES_COUNT(bc_names), kind);
}

/* Each face a known kind, periodic on both faces of an axis or on neither
 * (MPM_EINPUT), and periodic exactly along the mesh's periodic axes
 * (MPM_EINVAL). */
static int check_kinds(const int *kind, const mpm_mesh *m, mpm_err *err)
{
  const int dim = m->dim;
  const char *const *names = face_names[dim == 3];
  for (int f = 0; f < 2 * dim; f++)
    if (!mpm_bc_kind_name(kind[f]))
      return mpm_err_set(err, MPM_EINVAL, "boundary '%s': unknown kind %d", names[f], kind[f]);
  for (int a = 0; a < dim; a++) {
    const int lo = kind[2 * a] == MPM_BC_PERIODIC, hi = kind[2 * a + 1] == MPM_BC_PERIODIC;
    if (lo != hi)
      return mpm_err_set(err, MPM_EINPUT, "boundary: '%s' and '%s' must both be periodic or neither",
                         names[2 * a], names[2 * a + 1]);
  }
  for (int a = 0; a < dim; a++)
    if ((kind[2 * a] == MPM_BC_PERIODIC) != (m->periodic[a] != 0))
      return mpm_err_set(err, MPM_EINVAL, "boundary: periodic %s disagree with the mesh",
                         dim == 3 ? "faces" : "edges");
  return MPM_OK;
}

int mpm_bc_setup(mpm_bc *bc, const mpm_mesh *m, const int face[], mpm_err *err)
{
  int rc = check_kinds(face, m, err);
  if (rc != MPM_OK)
    return rc;
  bc->dim = m->dim;
  for (int f = 0; f < 6; f++)
    bc->face[f] = f < 2 * m->dim ? face[f] : MPM_BC_FREE;
  bc->nnodes = m->nnodes;
  bc->out_face = -1;
  bc->open = 0;
  bc->mask[1] = NULL;
  bc->normal = NULL;
  bc->fix = bc->mask[0] = calloc((size_t)m->nnodes, 1);
  if (!bc->fix)
    return mpm_err_set(err, MPM_ENOMEM, "boundary mask: out of memory");
  /* every logical node on a face: an aliased node gets the bits of both its
   * copies, none from a periodic face */
  int c[3];
  const int kz = m->dim == 3 ? m->nz : 0;
  for (c[2] = 0; c[2] <= kz; c[2]++)
    for (c[1] = 0; c[1] <= m->ny; c[1]++)
      for (c[0] = 0; c[0] <= m->nx; c[0]++) {
        unsigned char b = 0;
        for (int f = 0; f < 2 * m->dim; f++)
          if (c[f / 2] == (f % 2 ? m->n[f / 2] : 0))
            b |= mpm_bc_wall_bits(bc->face[f], f / 2, m->dim);
        bc->fix[mpm_mesh_node(m, c[0], c[1], c[2])] |= b;
      }
  return MPM_OK;
}

void mpm_bc_clear(mpm_bc *bc)
{
  free(bc->mask[0]);
  free(bc->mask[1]);
  free(bc->normal);
  bc->fix = bc->mask[0] = bc->mask[1] = NULL;
  bc->normal = NULL;
  bc->nnodes = 0;
  bc->out_face = -1;
  bc->open = 0;
}
