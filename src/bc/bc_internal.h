/* bc_internal.h: checks shared by the 2D edge conditions (bc.c) and the 3D
 * face conditions (bc3.c); private to bc/. */
#ifndef MPM_BC_BC_INTERNAL_H
#define MPM_BC_BC_INTERNAL_H

#include "core/error.h"

/* Check the kinds of the 2 dim sides (edges or faces, named names[], in
 * pairs of opposites along axis 0, 1, ...): each a known kind, periodic on
 * both of a pair or on neither (MPM_EINPUT), and periodic exactly along the
 * axes where the mesh is (periodic[axis], MPM_EINVAL). `what` is "edges" or
 * "faces", for the message. */
int mpm_bc_check_kinds(const int *kind, int dim, const int *periodic,
                       const char *const *names, const char *what, mpm_err *err);

#endif
