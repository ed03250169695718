/* kernels.c: the kernels of the step for the plane and for 3D, from one
 * source (kernels.inc) compiled with the dimension a constant, and their
 * const tables (solver_internal.h). */
#include "solver/solver_internal.h"

#include <stdlib.h>
#include <string.h>

/* Where a point's weights come from (kernels.inc). */
enum { W_LOCATED = 0, W_ELEMENT, W_LIST, W_SEPARABLE };

#define D 2
#define KD(name) name##2
#include "solver/kernels.inc"
#undef D
#undef KD

#define D 3
#define KD(name) name##3
#include "solver/kernels.inc"
#undef D
#undef KD
