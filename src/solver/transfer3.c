/* transfer3.c: the transfers of the 3D module (MODEL.md section 2, steps
 * 2-4 on the box mesh): the kernels of transfer.inc compiled with DIM 3,
 * applied to the stored 3D stencil (shape3.h) and the faces' conditions
 * (bc3.h), with APIC's affine part as in the plane (transfer.c). The parallel structure of the grid phase is transfer.c's
 * (mpm_sim_in_grid3), shared with the plane step. */
#include "solver/transfer.h"

#define DIM 3
#define TR(name) name##3
#define TR_BC mpm_bc3
#define TR_BC_APPLY(bc, i, v) mpm_bc3_apply_node(bc, i, v)
#include "solver/transfer.inc"

/* The stored weights of point p: count, nodes, S and the gradients. */
static inline int weights3(const mpm_sim *s, size_t p, const int **node, const double **S,
                           const double *g[3])
{
  const mpm_shape_stencil *st = s->st;
  const size_t o = p * (size_t)st->w;
  *node = st->node + o;
  *S = st->S + o;
  g[0] = st->dSx + o;
  g[1] = st->dSy + o;
  g[2] = st->dSz + o;
  return st->count[p];
}

void mpm_sim_in_p2g_band3(const mpm_sim *s, int k, const double b[3])
{
  const mpm_points *P = s->pts;
  const mpm_mesh_bands *bd = s->bands;
  const int apic = s->cfg.time.transfer == MPM_TRANSFER_APIC;
  for (int q = bd->start[k]; q < bd->start[k + 1]; q++) {
    const size_t p = (size_t)bd->idx[q];
    const int *node;
    const double *S, *g[3];
    const int c = weights3(s, p, &node, &S, g);
    const double m = P->mass[p], V = P->vol[p];
    double sxx = P->sxx[p], syy = P->syy[p], szz = P->szz[p];
    if (s->usum && s->uof[p] >= 0) {             /* B-bar: s_m -> the unit's mean */
      const double d = mpm_sim_in_bbar_shift(s, s->uel, p);
      sxx += d;
      syy += d;
      szz += d;
    }
    const double sxy = P->sxy[p], syz = P->syz[p], szx = P->szx[p];
    const double a[6] = {m * P->vx[p], m * P->vy[p], m * P->vz[p], m * b[0], m * b[1], m * b[2]};
    const double ad[3][6] = {{0.0, 0.0, 0.0, -V * sxx, -V * sxy, -V * szx},
                             {0.0, 0.0, 0.0, -V * sxy, -V * syy, -V * syz},
                             {0.0, 0.0, 0.0, -V * szx, -V * syz, -V * szz}};
    mpm_tr_p2g3(s->nm, s->nq3, c, node, S, g, m, a, ad);
    if (apic) {                                   /* (mv)_i += S m C_p (x_i - x_p) */
      const double C[9] = {P->cxx[p], P->cxy[p], P->cxz[p], P->cyx[p], P->cyy[p],
                           P->cyz[p], P->czx[p], P->czy[p], P->czz[p]};
      const double xp[3] = {P->x[p], P->y[p], P->z[p]};
      for (int j = 0; j < c; j++) {
        double e[3];
        mpm_sim_in_node_offset3(s, node[j], xp, e);
        mpm_tr_p2g_affine3(s->nq3[node[j]], S[j] * m, C, e);
      }
    }
  }
}

void mpm_sim_in_grid_node3(mpm_sim *s, int i, const double b[3], double idt)
{
  mpm_tr_grid_node3(&s->bc3, i, s->bc3.fix[i] != 0, s->nm[i], s->nq3[i], b, s->dt, idt,
                    s->mtiny, s->mlight);
}

void mpm_sim_in_gather3(const mpm_sim *s, size_t p, double vg[3], double ag[3], double L[9])
{
  const int *node;
  const double *S, *g[3];
  const int c = weights3(s, p, &node, &S, g);
  mpm_tr_gather3((const double (*)[6])s->nq3, c, node, S, g, vg, ag, L);
}

void mpm_sim_in_affine3(mpm_sim *s, size_t p, const double vg[3], double L[9])
{
  const int *node;
  const double *S, *g[3];
  const int c = weights3(s, p, &node, &S, g);
  if (s->mlight > 0.0)                                   /* delta weights */
    mpm_tr_gather_empty3(s->nm, s->mtiny, s->stiny, c, node, S, g, vg, L);
  mpm_points *P = s->pts;
  double *const C[9] = {&P->cxx[p], &P->cxy[p], &P->cxz[p], &P->cyx[p], &P->cyy[p],
                        &P->cyz[p], &P->czx[p], &P->czy[p], &P->czz[p]};
  for (int k = 0; k < 9; k++)
    *C[k] = L[k];
}
