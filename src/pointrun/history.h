/* history.h: prescribed velocity-gradient histories L(t) for driving one
 * material point (the constitutive driver and its verification, MODEL.md
 * section 4).
 *
 * A history is a table of nodes (t_k, L_k), times strictly increasing, with L
 * linear in t between nodes; only the in-plane components Lxx, Lxy, Lyx, Lyy
 * are nonzero (plane strain, L_ij = d v_i / d x_j). The [DK15] Appendix B
 * history is such a table (its Heaviside factors multiply ramps that vanish
 * where they switch, so it is continuous and piecewise linear). Histories are
 * read from and written to CSV files by io/history.h. */
#ifndef MPM_POINTRUN_HISTORY_H
#define MPM_POINTRUN_HISTORY_H

#include <stddef.h>

#include "core/error.h"
#include "core/tensor3.h"

enum { MPM_HISTORY_NCOL = 5 };  /* values of a node: t, Lxx, Lxy, Lyx, Lyy */

typedef struct mpm_history {
  size_t n;      /* nodes (>= 2) */
  double *t;     /* node times [s], strictly increasing */
  double *L;     /* 4 n values: Lxx, Lxy, Lyx, Lyy of node k at L[4k..4k+3] [1/s] */
} mpm_history;

/* Table of n nodes, all zero. */
mpm_history *mpm_pointrun_history_alloc(size_t n);
void mpm_pointrun_history_free(mpm_history *h);  /* accepts NULL */

/* The [DK15] App. B history on [0, 1.25] s:
 *   L = L_shear + [H(t-.25) - H(t-.5)] L_com + [H(t-.75) - H(t-1)] L_ext,
 *   L_shear = 0.05 e_x(x)e_y, L_com = (|8t-3| - 1)(e_x e_x + e_y e_y),
 *   L_ext = (1 - |8t-7|)(e_x e_x + e_y e_y). */
int mpm_pointrun_history_dk15(mpm_history **out, mpm_err *err);

static inline double mpm_pointrun_history_t_begin(const mpm_history *h) { return h->t[0]; }
static inline double mpm_pointrun_history_t_end(const mpm_history *h) { return h->t[h->n - 1]; }

/* Segment k with t_k <= t < t_{k+1} (clamped to 0 ... n-2). */
size_t mpm_pointrun_history_segment(const mpm_history *h, double t);

/* L(t) on segment k (linear in t there, also outside it). */
mpm_mat3 mpm_pointrun_history_eval_seg(const mpm_history *h, size_t k, double t);

/* L(t), linear between nodes, constant beyond the first and last node. */
mpm_mat3 mpm_pointrun_history_eval(const mpm_history *h, double t);

/* Mean of L over [a, b] (exact for the piecewise-linear table), a < b. */
mpm_mat3 mpm_pointrun_history_mean(const mpm_history *h, double a, double b);

#endif
